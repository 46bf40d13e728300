"""Files in and out: scenario TOML files, result files, bundled examples, IMU (gyroscope) recordings."""

from .bundled import EXAMPLES, copy_example, example_path
from .gyro import (RECORDINGS, TRIALS, GyroFileError, GyroRecording, ImuRecording, parse_gyro, read_gyro, read_imu,
                   recording_path)
from .results import ResultError, load_result, load_trajectory, save_result
from .run import run_scenario, summary
from .scenario import Scenario, ScenarioError, load_scenario, parse_scenario
from .schema import SchemaError

__all__ = ["EXAMPLES", "copy_example", "example_path", "ResultError", "load_result", "load_trajectory", "save_result",
           "run_scenario", "summary", "Scenario", "ScenarioError", "load_scenario", "parse_scenario",
           "SchemaError", "GyroFileError", "GyroRecording", "ImuRecording", "RECORDINGS", "TRIALS", "parse_gyro",
           "read_gyro", "read_imu", "recording_path"]
