"""``kreisel serve --recording broad_07``: the bundled BROAD trial, its estimated attitude beside the reference."""

import os
import re
import subprocess
import sys

from .test_as_a_user import SRC, kreisel, usage_error


def test_serve_replays_the_bundled_trial_by_name(tmp_path, interrupt):
    import httpx

    usage_error(kreisel("serve", "--recording", "broad_7", "--no-browser", cwd=tmp_path), "broad_7")
    env = dict(os.environ, PYTHONPATH=str(SRC))
    server = subprocess.Popen([sys.executable, "-m", "kreisel", "serve", "--recording", "broad_07", "--port", "0",
                               "--no-browser"], cwd=tmp_path, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    try:
        url = None
        for line in server.stdout:
            found = re.search(r"(http://127\.0\.0\.1:\d+/)(\?token=[\w-]+)", line)
            if found:
                url, token = found.groups()
                break
        assert url, "kreisel serve did not print its URL"
        assert httpx.get(url + "api/recording", timeout=60).status_code == 403
        data = httpx.get(url + "api/recording" + token, timeout=600).json()
        assert data["kind"] == "attitude" and data["source"].endswith("broad_07_fast_rotation_60s.npz")
        assert len(data["q"]) == len(data["q_ref"]) == 17142
        assert 1.0 < data["rmse_deg"]["total"] < 2.5
    finally:
        interrupt(server, 60)
