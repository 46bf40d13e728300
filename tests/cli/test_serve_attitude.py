"""``kreisel serve --recording broad_07``: the bundled BROAD trial, its estimated attitude beside the reference."""


def test_serve_replays_the_bundled_trial_by_name(kreisel, usage_error, serve, tmp_path):
    import httpx

    usage_error(kreisel("serve", "--recording", "broad_7", "--no-browser", cwd=tmp_path), "broad_7")
    with serve("--recording", "broad_07", cwd=tmp_path) as (url, token):
        assert httpx.get(url + "api/recording", timeout=60).status_code == 403
        data = httpx.get(url + "api/recording" + token, timeout=600).json()
        assert data["kind"] == "attitude" and data["source"].endswith("broad_07_fast_rotation_60s.npz")
        assert len(data["q"]) == len(data["q_ref"]) == 17142
        assert 1.0 < data["rmse_deg"]["total"] < 2.5
