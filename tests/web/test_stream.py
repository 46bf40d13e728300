"""The viewer's WebSocket stream ``/api/stream`` through FastAPI's test client."""

import numpy as np
import pytest
from starlette.websockets import WebSocketDisconnect

from kreisel.web import create_app
from kreisel.web.session import MAX_SAMPLES, MAX_STREAM_SAMPLES

CHUNK = 60
TENNIS = {"moments": [1.0, 2.0, 3.0], "omega": [0.01, 1.0, 0.01], "t_end": 20.0, "n_samples": 401,
          "method": "dop853"}
LAGRANGE = {"moments": [1.0, 1.0, 0.5], "omega": [0.0, 0.0, 6.0], "euler_deg": [0.0, 30.0, 0.0], "mgl": 1.0,
            "t_end": 5.0, "n_samples": 301}
ARRAYS = ("t", "q", "omega", "omega_space", "J", "J_norm", "energy", "kinetic")


@pytest.fixture(scope="module")
def client(app_client):
    return app_client(chunk_samples=CHUNK)


def stream(client, body, cancel_after=None):
    """All messages of one stream, and the close code; sends "cancel" after ``cancel_after`` chunks."""
    messages = []
    with client.websocket_connect("/api/stream") as ws:
        ws.send_json(body)
        while True:
            try:
                message = ws.receive_json()
            except WebSocketDisconnect as closed:
                return messages, closed.code
            messages.append(message)
            if message["type"] == "chunk" and message["index"] + 1 == cancel_after:
                ws.send_text("cancel")


def joined(messages):
    chunks = [m for m in messages if m["type"] == "chunk"]
    return {key: np.concatenate([np.asarray(c[key]) for c in chunks]) for key in chunks[0] if key not in
            ("type", "index", "offset")}


def check_order(messages):
    """start, chunks in order with consecutive sample offsets, done."""
    start, *chunks, done = messages
    assert start["type"] == "start" and done["type"] == "done"
    assert [c["type"] for c in chunks] == ["chunk"] * start["n_chunks"]
    assert [c["index"] for c in chunks] == list(range(len(chunks)))
    offsets = np.cumsum([0] + [len(c["t"]) for c in chunks])
    assert [c["offset"] for c in chunks] == offsets[:-1].tolist() and offsets[-1] == start["n_samples"]
    t = np.concatenate([c["t"] for c in chunks])
    assert np.all(np.diff(t) > 0)
    return start, done


def test_exact_free_top_streams_the_one_shot_run_bit_for_bit(client):
    body = {"form": dict(TENNIS, n_samples=2001, t_end=60.0), "exact": True}
    messages, code = stream(client, body)
    assert code == 1000
    start, done = check_order(messages)
    assert start["n_chunks"] == -(-2001 // CHUNK) and start["method"] == "exact"
    one_shot = client.post("/api/run", json=body).json()
    got = joined(messages)
    for key in ARRAYS:  # the closed form is evaluated per sample: chunking changes nothing
        np.testing.assert_array_equal(got[key], one_shot[key], err_msg=key)
    assert done["integrals"] == one_shot["integrals"]
    for key in ("kind", "title", "inertia", "gravity", "analysis", "form", "toml"):
        assert start[key] == one_shot[key], key
    # the racket flips: omega_2 changes sign within the run
    assert got["omega"][:, 1].min() < -0.9 < 0.9 < got["omega"][:, 1].max()


@pytest.mark.parametrize(("form", "tolerance"), [
    # dop853 restarts its error control at each chunk: agreement to its tolerance (rtol 1e-12, ~1e-11 seen)
    (TENNIS, 1e-9),
    (LAGRANGE, 1e-9),
    # rk4 steps each interval between samples on its own: the same arithmetic either way
    (dict(TENNIS, method="rk4", dt=0.01), 1e-14),
    # the splitting merges the half flows of the steps on either side of a sample within one run, a
    # chunk's run applies them apart at its last sample: the same flows, rounded differently
    # (<= 4e-14 seen after the flip, which amplifies round-off)
    (dict(TENNIS, method="splitting", dt=0.01), 1e-12),
])
def test_chunked_integration_agrees_with_the_one_shot_run(client, form, tolerance):
    messages, code = stream(client, {"form": form})
    assert code == 1000
    start, done = check_order(messages)
    one_shot = client.post("/api/run", json={"form": form}).json()
    got = joined(messages)
    np.testing.assert_array_equal(got["t"], one_shot["t"])
    for key in ("q", "omega", "omega_space", "J", "energy"):
        scale = max(1.0, np.max(np.abs(one_shot[key])))
        np.testing.assert_allclose(got[key], one_shot[key], rtol=0, atol=tolerance * scale, err_msg=key)
    assert start["analysis"] == one_shot["analysis"]
    for streamed, whole in zip(done["integrals"], one_shot["integrals"], strict=True):
        assert streamed["name"] == whole["name"] and streamed["initial"] == whole["initial"]
        assert streamed["relative"] == pytest.approx(whole["relative"], abs=tolerance)


def test_foucault_streams_in_one_chunk(client):
    from kreisel.web.presets import preset_text

    short = preset_text("foucault").replace("duration = 3600.0", "duration = 300.0")
    messages, code = stream(client, {"toml": short})
    assert code == 1000
    start, done = check_order(messages)
    one_shot = client.post("/api/run", json={"toml": short}).json()
    assert start["kind"] == "foucault" and start["n_chunks"] == 1
    np.testing.assert_array_equal(messages[1]["swing_azimuth"], one_shot["swing_azimuth"])
    assert done["integrals"] == one_shot["integrals"]


def test_streams_allow_more_samples_than_one_reply(client):
    form = dict(TENNIS, n_samples=MAX_SAMPLES + 1, t_end=100.0)
    assert client.post("/api/run", json={"form": form, "exact": True}).status_code == 422
    messages, code = stream(client, {"form": form, "exact": True}, cancel_after=2)
    assert code == 1000 and messages[0]["n_samples"] == MAX_SAMPLES + 1


@pytest.mark.parametrize(("body", "status", "words"), [
    ({"form": dict(TENNIS, n_samples=MAX_STREAM_SAMPLES + 1)}, 422, f"at most {MAX_STREAM_SAMPLES}"),
    ({"form": dict(TENNIS, method="rk4", dt=1e-9)}, 422, "steps is too many"),
    ({"form": dict(TENNIS, t_end=1e9)}, 422, "turns"),
    ({"form": LAGRANGE, "exact": True}, 422, "torque-free"),
    ({"form": dict(TENNIS, moments=[1.0, 1.0, 3.0])}, 400, "not a physical rigid body"),
    ({"form": dict(TENNIS, method="euler")}, 422, "form.method"),
    ({"toml": "not toml ["}, 400, "<scenario>"),
    ({"preset": "nope"}, 404, "preset must be one of"),
    ({"preset": "tennis_racket", "toml": "x"}, 400, "exactly one"),
    ({"form": {"moments": [1.0, 2.0]}}, 422, "form.moments"),
    ("run the racket please", 422, "Invalid JSON"),
])
def test_bad_requests_get_a_reason_then_close(client, body, status, words):
    with client.websocket_connect("/api/stream") as ws:
        ws.send_text(body) if isinstance(body, str) else ws.send_json(body)
        error = ws.receive_json()
        with pytest.raises(WebSocketDisconnect) as closed:
            ws.receive_json()
    assert error["type"] == "error" and error["status"] == status
    assert words in error["detail"]
    assert closed.value.code == 1008


def test_cancel_stops_the_run(client):
    form = dict(TENNIS, n_samples=CHUNK * 1000, t_end=1000.0)
    messages, code = stream(client, {"form": form, "exact": True}, cancel_after=1)
    assert code == 1000
    assert messages[0]["type"] == "start" and messages[-1]["type"] == "cancelled"
    chunks = [m for m in messages if m["type"] == "chunk"]
    # the chunk in progress when "cancel" arrives may still be sent, nothing after it
    assert 1 <= len(chunks) < messages[0]["n_chunks"] and not any(m["type"] == "done" for m in messages)
    assert messages[-1]["samples"] == sum(len(c["t"]) for c in chunks)


def test_binary_request_and_chunk_size_are_checked(client):
    with client.websocket_connect("/api/stream") as ws:
        ws.send_bytes(b"\x00")
        assert "JSON text" in ws.receive_json()["detail"]
    with pytest.raises(ValueError, match="chunk_samples"):
        create_app(chunk_samples=1)
