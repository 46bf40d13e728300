"""Only the viewer's own pages reach it; bodies and runs are bounded; every refusal is a 4xx with a reason."""

import json
import socket
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from starlette.websockets import WebSocketDisconnect

from kreisel.web.runner import Limits

from .conftest import RELAXED, authorization

TENNIS = {"moments": [1.0, 2.0, 3.0], "omega": [0.01, 1.0, 0.01], "t_end": 2.0, "n_samples": 21}
# a body under stiff damping: decay rate c / I = 1e18 /s, so the explicit adaptive integrator's steps stay
# near 1e-18 s and the run would take years; the up-front workload check counts turns, which damping only
# lowers (ω0 = 0.1 rad/s, 30 s: half a turn)
RUNAWAY = {"toml": """title = "stiff damping"
[body]
moments = [1e-6, 1e-6, 1e-6]
[initial]
omega = [0.1, 0.0, 0.0]
[[torque]]
kind = "damping"
coefficient = 1e12
[integration]
t_end = 30.0
n_samples = 1000
"""}
FOREIGN = ["http://127.0.0.1:58771", "http://evil.example", "null"]


@pytest.fixture(scope="module")
def client(app_client):
    return app_client()


@pytest.mark.parametrize("origin", FOREIGN)
def test_a_foreign_origin_is_refused_over_http_and_websocket(client, origin):
    for method, path, body in (("GET", "/api/initial", None), ("POST", "/api/run", {"form": TENNIS}),
                               ("POST", "/api/scenario", {"form": TENNIS})):
        response = client.request(method, path, json=body, headers={"Origin": origin})
        assert response.status_code == 403 and "origin" in response.json()["detail"]
    with pytest.raises(WebSocketDisconnect) as refused:
        with client.websocket_connect("/api/stream", headers={"Origin": origin}):
            pass
    assert refused.value.code == 1008


def test_a_foreign_host_is_refused(client):
    # a DNS-rebinding page names its own domain as the host, even when it resolves to 127.0.0.1
    for host in ("rebind.example", "rebind.example:8000", "127.0.0.2"):
        response = client.get("/api/initial", headers={"Host": host})
        assert response.status_code == 403 and "host" in response.json()["detail"]
    with pytest.raises(WebSocketDisconnect):
        with client.websocket_connect("/api/stream", headers={"Host": "rebind.example"}):
            pass
    # the server's own names and origin are accepted
    for host in ("127.0.0.1", "localhost:8000", "[::1]:8000"):
        origin = f"http://{host}"
        assert client.get("/api/presets", headers={"Host": host, "Origin": origin}).status_code == 200


def test_live_server_refuses_foreign_origin_host_and_port(live_server):
    import httpx
    from websockets.exceptions import InvalidStatus
    from websockets.sync.client import connect

    url, app = live_server
    token = authorization(app)
    port = url.rstrip("/").rsplit(":", 1)[1]
    assert httpx.get(url + "api/initial", headers={"Origin": url.rstrip("/"), **token}).status_code == 200
    assert httpx.get(url + "api/initial", headers={"Host": f"rebind.example:{port}", **token}).status_code == 403
    # the right name on another port is another server
    assert httpx.get(url + "api/initial", headers={"Host": "127.0.0.1:1", **token}).status_code == 403
    stream = url.replace("http", "ws") + "api/stream"
    for origin in FOREIGN:
        with pytest.raises(InvalidStatus) as refused:
            connect(stream, origin=origin, open_timeout=30, additional_headers=token)
        assert refused.value.response.status_code == 403
    with connect(stream, origin=url.rstrip("/"), open_timeout=30, additional_headers=token) as ws:
        ws.send(json.dumps({"preset": "nope"}))
        assert json.loads(ws.recv(timeout=30))["status"] == 404


def _raw(url, request, read_body=False, app=None):
    """Send raw bytes to the live server and return the status line and answer, without sending a body.

    With ``app``, its token is added to the request's headers.
    """
    host, port = url.split("//")[1].rstrip("/").split(":")
    if app is not None:
        line, _, rest = request.partition(b"\r\n")
        request = line + b"\r\nAuthorization: token " + app.state.viewer.token.encode() + b"\r\n" + rest
    with socket.create_connection((host, int(port)), timeout=30) as sock:
        sock.sendall(request)
        answer = b""
        while b"\r\n\r\n" not in answer or (read_body and not answer.endswith(b"}")):
            chunk = sock.recv(65536)
            if not chunk:
                break
            answer += chunk
    return answer.decode("latin-1")


def test_oversized_bodies_are_refused_before_they_are_read(live_server):
    url, app = live_server
    host = url.split("//")[1].rstrip("/")
    limit = app.state.viewer.limits.max_body
    # 400 MB announced, none sent: the answer comes at once, so the body was never read
    answer = _raw(url, (f"POST /api/run HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\n"
                        f"Content-Length: 400000000\r\n\r\n").encode(), read_body=True, app=app)
    assert answer.startswith("HTTP/1.1 413") and f"larger than {limit} bytes" in answer
    # a chunked body is counted as it arrives and refused once it passes the limit
    chunk = b"x" * 65536
    chunks = (b"%x\r\n" % len(chunk) + chunk + b"\r\n") * (limit // len(chunk) + 2)
    answer = _raw(url, (f"POST /api/run HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\n"
                        "Transfer-Encoding: chunked\r\n\r\n").encode() + chunks, read_body=True, app=app)
    assert answer.startswith("HTTP/1.1 413")


def test_oversized_websocket_request_is_refused(client):
    with client.websocket_connect("/api/stream") as ws:
        ws.send_text(json.dumps({"toml": "#" * 2_000_000}))
        error = ws.receive_json()
        with pytest.raises(WebSocketDisconnect) as closed:
            ws.receive_json()
    assert error["status"] == 413 and closed.value.code == 1008 and "larger than" in closed.value.reason


ATTITUDE = "[body]\nmoments = [1.0, 2.0, 3.0]\n[initial]\nomega = [0.0, 1.0, 0.0]\n[initial.attitude]\n{}\n" \
           "[integration]\nt_end = 1.0\nn_samples = 11\n"
MALFORMED = [
    b"", b"null", b"[]", b"{}", b"42", b'"text"', b"{", b"{'form': 1}", b"\xff\xfe", b'{"form": null}',
    b'{"form": {}}', b'{"form": []}', b'{"form": "x"}', b'{"toml": 5}', b'{"toml": null, "preset": null}',
    b'{"preset": ["tennis_racket"]}', b'{"preset": "../../etc/passwd"}', b'{"toml": "[body"}', b'{"toml": ""}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0]}, "exact": "yes"}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0]}, "exact": 1}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "mgl": NaN}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "mgl": -1}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "mgl": "1"}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, Infinity]}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 1e999]}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1]}}',
    b'{"form": {"moments": [0, 2, 3], "omega": [0, 1, 0]}}',
    b'{"form": {"moments": [1, 1, 3], "omega": [0, 1, 0]}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "n_samples": 1.5}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "n_samples": 0}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "n_samples": 1e30}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "lever_axis": 3}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "lever_axis": true}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "method": "euler"}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "method": "rk4"}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "method": "rk4", "dt": 1e-300}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "t_end": -1}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "t_end": 1e300}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "euler_deg": [1, 2]}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "title": 7}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0], "colour": "red"}}',
    b'{"form": {"moments": [1, 2, 3], "omega": [0, 1, 0]}, "extra": 1}',
    json.dumps({"toml": ATTITUDE.format('seq = "ZXQ"\neuler = [1.0, 2.0, 3.0]')}).encode(),
    json.dumps({"toml": ATTITUDE.format('seq = "ZZX"\neuler = [1.0, 2.0, 3.0]')}).encode(),
    json.dumps({"toml": ATTITUDE.format("quat = [0.0, 0.0, 0.0, 0.0]")}).encode(),
    json.dumps({"toml": ATTITUDE.format("matrix = [[1.0, 0, 0], [0, 2.0, 0], [0, 0, 1.0]]")}).encode(),
    json.dumps({"toml": "x = " + "[" * 5000 + "]" * 5000}).encode(),
    json.dumps({"toml": ATTITUDE.replace("[integration]", "[[torque]]\nkind = 'gravity'\nweight = 1.0\n"
                                                         "lever = [0.0, 0.0, 0.0]\n[integration]")
                .format("")}).encode(),
]


def _refused_with_reason(response):
    assert 400 <= response.status_code < 500, (response.status_code, response.text[:300])
    detail = response.json()["detail"]
    assert isinstance(detail, str) and detail


@pytest.mark.parametrize("body", MALFORMED)
def test_every_malformed_body_gets_a_4xx_with_a_reason(client, body):
    for path in ("/api/scenario", "/api/run", "/api/export?format=csv"):
        _refused_with_reason(client.post(path, content=body, headers={"Content-Type": "application/json"}))
    with client.websocket_connect("/api/stream") as ws:
        ws.send_bytes(body) if not body.strip() else ws.send_text(body.decode("utf-8", errors="replace"))
        error = ws.receive_json()
        with pytest.raises(WebSocketDisconnect) as closed:
            ws.receive_json()
    assert error["type"] == "error" and 400 <= error["status"] < 500 and error["detail"]
    assert closed.value.code == 1008 and closed.value.reason


def test_bad_query_and_content_type_get_a_4xx(client):
    _refused_with_reason(client.post("/api/export?format=exe", json={"form": TENNIS}))
    _refused_with_reason(client.post("/api/run", content=b"moments=1", headers={"Content-Type": "text/plain"}))
    _refused_with_reason(client.post("/api/run", content=b"{}", headers={"Content-Length": "two"}))


_json = st.recursive(st.none() | st.booleans() | st.integers(-10**30, 10**30) | st.floats() | st.text(max_size=8),
                     lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=6), inner,
                                                                                 max_size=4), max_leaves=12)
_FIELDS = ["title", "moments", "omega", "euler_deg", "mgl", "lever_axis", "method", "t_end", "n_samples", "dt"]


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(fields=st.dictionaries(st.sampled_from(_FIELDS), _json, max_size=6),
       top=st.dictionaries(st.sampled_from(["preset", "toml", "exact", "form"]), _json, max_size=2))
def test_random_bodies_never_answer_a_server_error(client, fields, top):
    body = {**top, "form": {**TENNIS, **fields}}
    text = json.dumps(body, allow_nan=True)
    response = client.post("/api/scenario", content=text, headers={"Content-Type": "application/json"})
    assert response.status_code < 500, response.text[:300]
    assert response.status_code == 200 or response.json()["detail"]


def _alive(pid):
    try:
        with open(f"/proc/{pid}/status") as fh:
            return "zombie" not in fh.read()
    except FileNotFoundError:
        return False


def _wait_until(condition, seconds):
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            return False
        time.sleep(0.05)
    return True


def test_a_runaway_run_is_cut_off_by_its_time_limit(app_client):
    # only the time limit can stop it (no step budget to speak of)
    limits = Limits(wall_seconds=3.0, grace_seconds=0.5, queue_seconds=900.0, max_steps=10**15)
    client = app_client(limits=limits)
    runner = client.app.state.viewer.runner
    # a worker is started, with kreisel's compiled code loaded in it, by an ordinary run without a time
    # limit first: on a loaded machine that alone can outlast 3 s
    runner.limits = RELAXED
    assert client.post("/api/run", json={"form": TENNIS}).status_code == 200
    runner.limits = limits
    start = time.monotonic()
    response = client.post("/api/run", json=RUNAWAY)
    elapsed = time.monotonic() - start
    assert response.status_code == 422 and "limit of 3 s" in response.json()["detail"]
    # not before the limit, and not the hours the run would take: load only adds to the first bound's margin
    assert 3.0 <= elapsed < 300.0
    with client.websocket_connect("/api/stream") as ws:
        ws.send_json(RUNAWAY)
        error = ws.receive_json()
        with pytest.raises(WebSocketDisconnect) as closed:
            ws.receive_json()
    assert error["type"] == "error" and "limit of 3 s" in error["detail"]
    assert closed.value.code == 1011 and "limit" in closed.value.reason
    # the worker stuck in compiled code was ended, not left computing
    assert not runner.busy and all(_alive(pid) for pid in runner.workers)


def test_a_runaway_run_is_cut_off_by_its_step_budget(app_client):
    # no wall-clock limit bites: the steps the run actually takes stop it
    client = app_client(limits=Limits(wall_seconds=900.0, queue_seconds=900.0, max_steps=20_000))
    response = client.post("/api/run", json=RUNAWAY)
    assert response.status_code == 422
    assert "budget of 20000 integration steps" in response.json()["detail"]
    with client.websocket_connect("/api/stream") as ws:
        ws.send_json(RUNAWAY)
        messages = [ws.receive_json()]
        while messages[-1]["type"] == "start" or messages[-1]["type"] == "chunk":
            messages.append(ws.receive_json())
        with pytest.raises(WebSocketDisconnect) as closed:
            ws.receive_json()
    assert messages[-1]["type"] == "error" and "budget of 20000 integration steps" in messages[-1]["detail"]
    assert closed.value.code == 1011
    # an ordinary request stays far inside the same budget
    ordinary = {"form": {"moments": [1.0, 1.0, 1.0], "omega": [0.1, 0.0, 0.0], "euler_deg": [0.0, 30.0, 0.0],
                         "mgl": 1.0, "t_end": 30.0, "n_samples": 1000}}
    assert client.post("/api/run", json=ordinary).status_code == 200
    with pytest.raises(ValueError, match="max_steps"):
        Limits(max_steps=0)


def test_a_run_is_stopped_when_its_websocket_client_leaves(app_client):
    client = app_client(limits=RELAXED)
    runner = client.app.state.viewer.runner
    with client.websocket_connect("/api/stream") as ws:
        ws.send_json(RUNAWAY)
        assert _wait_until(lambda: runner.busy, 60)
        pid = next(iter(runner.busy)).process.pid
        time.sleep(0.5)
    assert _wait_until(lambda: not _alive(pid), 10), "the run went on after its client left"
    assert _wait_until(lambda: not runner.busy, 10)


def test_a_run_is_stopped_when_its_http_client_leaves(live_server):
    url, app = live_server
    runner = app.state.viewer.runner
    host = url.split("//")[1].rstrip("/")
    body = json.dumps(RUNAWAY).encode()
    name, port = host.split(":")
    with socket.create_connection((name, int(port)), timeout=30) as sock:
        sock.sendall(f"POST /api/run HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\n"
                     f"Authorization: token {app.state.viewer.token}\r\n"
                     f"Content-Length: {len(body)}\r\n\r\n".encode() + body)
        assert _wait_until(lambda: runner.busy, 60)
        pid = next(iter(runner.busy)).process.pid
    assert _wait_until(lambda: not _alive(pid), 10), "the run went on after its client left"


def test_runs_beyond_the_slots_wait_then_are_refused(app_client):
    client = app_client(limits=Limits(slots=1, wall_seconds=900.0, queue_seconds=0.5, grace_seconds=0.5))
    runner = client.app.state.viewer.runner
    with client.websocket_connect("/api/stream") as ws:
        ws.send_json(RUNAWAY)
        assert _wait_until(lambda: runner.busy, 60)
        busy = client.post("/api/run", json={"form": TENNIS})
        assert busy.status_code == 503 and "busy" in busy.json()["detail"]
    assert _wait_until(lambda: not runner.busy, 10)
    assert client.post("/api/run", json={"form": TENNIS}).status_code == 200


def test_limits_are_checked():
    with pytest.raises(ValueError, match="slots"):
        Limits(slots=0)
    with pytest.raises(ValueError, match="wall_seconds"):
        Limits(wall_seconds=float("inf"))
    assert RELAXED.wall_seconds > Limits().wall_seconds


def test_a_wildcard_host_warns_and_names_the_server(monkeypatch, capsys):
    from kreisel.web import server

    started = {}

    class Server:
        def __init__(self, app):
            started["app"] = app

        def run(self, sockets):
            started["sockets"] = sockets

    # the socket is bound on the loopback interface: the test must not listen on every interface
    monkeypatch.setattr(server, "bind", lambda host, port: socket.create_server(("127.0.0.1", 0)))
    monkeypatch.setattr(server, "make_server", Server)
    server.serve(host="0.0.0.0", open_browser=False)
    out = capsys.readouterr().out
    assert "warning: --host 0.0.0.0 serves the viewer to every machine" in out
    assert started["sockets"][0].fileno() == -1  # closed on the way out
    assert not started["app"].state.viewer.runner.workers
