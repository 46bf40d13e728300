"""Who reaches the viewer: its token (as Jupyter's), and the Host allow-list on every interface."""

import json
import os
import pathlib
import re
import socket
import subprocess
import sys

import httpx
import pytest
from websockets.exceptions import InvalidStatus
from websockets.sync.client import connect

import kreisel
from kreisel.web import create_app
from kreisel.web.guard import Guard, machine_names

from .conftest import RELAXED, free_port, served

TOKEN = "t0ken-of-this-test"


@pytest.fixture(scope="module")
def tokened():
    """A viewer with a known token on loopback: (base URL, port)."""
    port = free_port()
    with served(create_app(port=port, limits=RELAXED, token=TOKEN), port) as url:
        yield url, port


def test_without_its_token_every_request_is_refused(tokened):
    url, port = tokened
    for token in (None, "", "wrong", TOKEN[:-1], TOKEN + "x"):
        query = {} if token is None else {"token": token}
        for path in ("", "api/presets", "api/initial", "static/viewer.js"):
            answer = httpx.get(url + path, params=query, timeout=30)
            assert answer.status_code == 403 and "token" in answer.json()["detail"], (path, token)
        answer = httpx.post(url + "api/run", json={"preset": "tennis_racket"}, params=query, timeout=30)
        assert answer.status_code == 403
        with pytest.raises(InvalidStatus) as refused:
            connect(url.replace("http", "ws") + "api/stream" + (f"?token={token}" if token is not None else ""),
                    open_timeout=30)
        assert refused.value.response.status_code == 403


def test_the_printed_url_sets_a_cookie_that_the_page_and_its_websocket_use(tokened):
    url, port = tokened
    with httpx.Client(timeout=30) as browser:
        page = browser.get(url, params={"token": TOKEN})
        assert page.status_code == 200 and "<title>" in page.text
        cookie = page.headers["set-cookie"]
        assert cookie.startswith(f"kreisel-token-{port}={TOKEN};") and "HttpOnly" in cookie
        assert "SameSite=Strict" in cookie
        # the page's own requests carry the cookie only, not the token
        assert browser.get(url + "api/presets").json()[0]["name"] == "tennis_racket"
        header = f"kreisel-token-{port}={TOKEN}"
    with connect(url.replace("http", "ws") + "api/stream", origin=url.rstrip("/"),
                 additional_headers={"Cookie": header}, open_timeout=30) as ws:
        ws.send(json.dumps({"preset": "nope"}))
        assert json.loads(ws.recv(timeout=30))["status"] == 404
    # a cookie of the viewer on another port is not this one's
    other = httpx.get(url + "api/presets", headers={"Cookie": f"kreisel-token-1={TOKEN}"}, timeout=30)
    assert other.status_code == 403


def test_scripts_give_the_token_in_a_header(tokened):
    url, _ = tokened
    for scheme in ("token", "Token", "Bearer"):
        assert httpx.get(url + "api/methods", headers={"Authorization": f"{scheme} {TOKEN}"}, timeout=30).json()
    assert httpx.get(url + "api/methods", headers={"Authorization": f"Basic {TOKEN}"}, timeout=30).status_code == 403


def test_a_random_token_per_app_unless_told_otherwise():
    first, second = create_app(), create_app()
    tokens = first.state.viewer.token, second.state.viewer.token
    assert tokens[0] != tokens[1] and min(len(t) for t in tokens) >= 40
    assert create_app(token="").state.viewer.token is None
    with pytest.raises(TypeError, match="token must be a string"):
        create_app(token=5)
    with pytest.raises(TypeError, match="allow_hosts must be a sequence of host names"):
        create_app(allow_hosts="lab.example")


def test_no_token_serves_any_local_process():
    port = free_port()
    with served(create_app(port=port, limits=RELAXED, token=""), port) as url:
        assert httpx.get(url + "api/methods", timeout=30).status_code == 200


def test_dns_rebinding_is_refused_on_every_interface():
    # the reproducer: a viewer started with --host 0.0.0.0 (served here on loopback only); a page of
    # rebind.attacker.example whose name now resolves to this machine sends its own Host and Origin
    port = free_port()
    app = create_app(host="0.0.0.0", port=port, limits=RELAXED, token="", allow_hosts=["kreisel-lab.example"])
    with served(app, port) as url:
        for name in ("rebind.attacker.example", "localhost.attacker.example", "127.0.0.1.nip.io"):
            host = f"{name}:{port}"
            answer = httpx.post(url + "api/run", json={"preset": "tennis_racket"}, timeout=30,
                                headers={"Host": host, "Origin": f"http://{host}"})
            assert answer.status_code == 403 and f"host {host} is not this server" in answer.json()["detail"]
            with pytest.raises(InvalidStatus):
                connect(url.replace("http", "ws") + "api/stream", origin=f"http://{host}", open_timeout=30,
                        additional_headers={"Host": host})
        # this machine's names and addresses, the address the request arrived at and the names the user
        # allowed all reach it
        for name in ("127.0.0.1", "localhost", socket.gethostname(), "kreisel-lab.example"):
            host = f"{name}:{port}"
            answer = httpx.get(url + "api/methods", headers={"Host": host, "Origin": f"http://{host}"}, timeout=30)
            assert answer.status_code == 200, (name, answer.text)


def test_the_host_list_on_a_wildcard_names_this_machine_and_no_wildcard():
    names = machine_names()
    assert socket.gethostname().lower() in names and "0.0.0.0" not in names
    guard = Guard(None, host="0.0.0.0", port=80, allow_hosts=["Lab.Example"])
    assert guard.refusal({"host": "lab.example:80"}) is None
    assert guard.refusal({"host": "192.0.2.7:80"}, server=("192.0.2.7", 80)) is None
    assert "is not this server" in guard.refusal({"host": "192.0.2.7:80"}, server=("192.0.2.8", 80))
    assert "is not this server" in guard.refusal({"host": "0.0.0.0:80"}, server=("127.0.0.1", 80))


def test_kreisel_serve_takes_the_token_and_host_names_it_is_given(interrupt):
    env = dict(os.environ, PYTHONPATH=str(pathlib.Path(kreisel.__file__).resolve().parents[1]))
    both = subprocess.run([sys.executable, "-m", "kreisel", "serve", "--token", "mine", "--no-token", "--no-browser"],
                          env=env, capture_output=True, text=True, timeout=300)
    assert both.returncode == 2 and "give --token or --no-token, not both" in both.stderr
    server = subprocess.Popen([sys.executable, "-m", "kreisel", "serve", "--port", "0", "--no-browser", "--token",
                               "my secret", "--allow-host", "lab.example"], env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True)
    try:
        printed = (re.search(r"(http://127\.0\.0\.1:(\d+)/)\?token=my%20secret\s", line) for line in server.stdout)
        found = next(filter(None, printed), None)
        assert found, "kreisel serve did not print its URL with the token it was given"
        url, port = found.groups()
        headers = {"Host": f"lab.example:{port}", "Authorization": "token my secret"}
        assert httpx.get(url + "api/methods", headers=headers, timeout=60).status_code == 200
        assert httpx.get(url + "api/methods", params={"token": "my secret"}, timeout=60).status_code == 200
        assert httpx.get(url + "api/methods", headers={**headers, "Host": f"other.example:{port}"},
                         timeout=60).status_code == 403
    finally:
        interrupt(server, 60)
