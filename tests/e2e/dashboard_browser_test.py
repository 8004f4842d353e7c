"""The dashboard in a real browser (Debian's headless Chromium through Selenium) against a real
fnet-server fed by real fnet-simd runs over DDS (domain 89): the page loads without console
errors; the curve's points are series.get's values (for several metrics, diagrams and
conventions); each new frame is on the curve within a second of the server's notification of its
commit; clicking a point shows that frame against the previous one — the change per contact, the
block table and the explained terms equal to blocks.get's and distance.get's; an ensemble's band is
ensemble.series. Screenshots are written to WORK_DIR/screenshots.

usage: dashboard_browser_test.py SOURCE_DIR BUILD_DIR WORK_DIR
"""

import os
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from dashboard_fixture import (Api, CommitWatch, Server, browser, close_browser, console_errors,  # noqa: E402
                               latencies, wait_until)

DOMAIN = 89
LIVE = ["--particles", "400", "--frames", "40", "--compression-speed", "1e-4", "--rho-final", "0.86",
        "--seed", "7", "--run-id", "live"]
ENSEMBLE = ["--particles", "120", "--frames", "12", "--compression-speed", "4e-3", "--rho-final", "0.86",
            "--ensemble", "ens", "--seeds", "1-3", "--jobs", "2"]


def js(driver, expression):
    return driver.execute_script("return " + expression)


def select_option(driver, element_id, value):
    from selenium.webdriver.support.ui import Select
    Select(driver.find_element("id", element_id)).select_by_value(value)


def same_curve(page, series):
    """The page's points against series.get's arrays: frame, ρ, Z, previous, value exactly."""
    if len(page) != len(series["frame"]):
        return f"{len(page)} points on the page, {len(series['frame'])} in series.get"
    for k, p in enumerate(page):
        expected = {"frame": series["frame"][k], "rho": series["rho"][k], "z": series["z"][k],
                    "previous": series["previous"][k], "value": series["value"][k],
                    "infinite": bool(series.get("infinite", [False] * len(page))[k])}
        got = {key: p[key] for key in expected}
        if got != expected:
            return f"point {k}: page {got}, series.get {expected}"
    return None


def changed_contacts(before, after, force):
    """Contacts whose force / mean force differs between the frames (present in one only: from or to 0)."""
    column = 2 if force == "normal" else 3

    def normalized(net):
        mean = net["mean_force"][force]
        return {(min(c[0], c[1]), max(c[0], c[1])): (abs(c[column]) / mean if mean > 0 else 0) for c in net["contacts"]}

    a, b = normalized(before), normalized(after)
    return sum(1 for key in set(a) | set(b) if b.get(key, 0) != a.get(key, 0) and (key in b or a[key] > 0))


def main():
    source_dir, build_dir, work = (os.path.abspath(a) for a in sys.argv[1:4])
    shutil.rmtree(work, ignore_errors=True)
    shots = os.path.join(work, "screenshots")
    os.makedirs(shots)
    server = Server(build_dir, source_dir, work, DOMAIN, ["--threads", "2"])
    driver = None
    try:
        api = Api(server.port)
        driver = browser(1400, 1050)
        driver.get(server.url)
        wait_until(lambda: js(driver, "window.fnetDashboard && fnetDashboard.rpc.open"), 20, "the page's WebSocket")
        assert "No run yet" in driver.find_element("id", "empty").text
        print("ok: the page loads and opens its WebSocket:", server.url)

        # Every frame's commit as a subscriber on TCP sees it, timed, while the run goes on.
        watch = CommitWatch(server.port)
        simd = server.simd(LIVE, os.path.join(work, "live.log"))
        wait_until(lambda: js(driver, "fnetDashboard.curve().length") >= 2, 300, "the run's first frames on the page")
        wait_until(lambda: js(driver, "fnetDashboard.curve().length") >= 30 or simd.poll() is not None, 300,
                   "30 frames on the page")
        driver.save_screenshot(os.path.join(shots, "live-run-midway.png"))
        assert simd.wait(600) == 0, open(os.path.join(work, "live.log")).read()
        summary = api.wait_for_frames("live", 40)
        wait_until(lambda: js(driver, "fnetDashboard.curve().length") == summary["frames"], 10, "every frame on the page")
        wait_until(lambda: js(driver, "fnetDashboard.runView.latest.frame") == summary["last_frame"], 10,
                   "the latest frame's network")
        watch.stop()

        # Latency: the page drew each frame within a second of the server's notification.
        live = latencies(driver, watch.times("live"))
        assert len(live) >= 5, f"only {len(live)} frames came after the page subscribed to the run"
        worst = max(live.values())
        assert worst < 1.0, f"a frame took {worst:.3f} s from its commit to the curve: {live}"
        print(f"ok: {len(live)} live frames each on the curve within {worst * 1000:.0f} ms of its commit "
              f"(median {sorted(live.values())[len(live) // 2] * 1000:.0f} ms)")

        # The curve is series.get's, for the default measure and for others chosen on the page.
        for metric, dim, essential in (("bottleneck", 1, "floor"), ("wasserstein2", 0, "floor"),
                                       ("wasserstein1", 1, "sentinel"), ("bottleneck", 0, "separate")):
            select_option(driver, "metric", metric)
            select_option(driver, "dim", str(dim))
            select_option(driver, "essential", essential)
            series = api.call("series.get", {"run": "live", "metric": metric, "dim": dim, "essential": essential})
            wait_until(lambda: same_curve(js(driver, "fnetDashboard.curve()"), series) is None, 20,
                       f"the page's curve of {metric} PD{dim} {essential}: "
                       f"{same_curve(js(driver, 'fnetDashboard.curve()'), series)}")
            print(f"ok: the curve of {metric} PD{dim} ({essential}) is series.get's, {len(series['frame'])} points")
        select_option(driver, "metric", "bottleneck")
        select_option(driver, "dim", "1")
        select_option(driver, "essential", "floor")
        series = api.call("series.get", {"run": "live", "metric": "bottleneck", "dim": 1})
        wait_until(lambda: same_curve(js(driver, "fnetDashboard.curve()"), series) is None, 20, "the default curve")
        driver.save_screenshot(os.path.join(shots, "live-run.png"))

        # Click the point of the largest distance: that frame against the previous one.
        values = [(v, f) for v, f, p in zip(series["value"], series["frame"], series["previous"]) if v is not None]
        _, frame = max(values)
        previous = series["previous"][series["frame"].index(frame)]
        from selenium.webdriver.common.action_chains import ActionChains
        canvas = driver.find_element("id", "curve")
        at = wait_until(lambda: js(driver, f"fnetDashboard.pointPosition({frame})"), 10, "the point's position")
        size = canvas.size
        ActionChains(driver).move_to_element_with_offset(canvas, at["x"] - size["width"] / 2,
                                                         at["y"] - size["height"] / 2).click().perform()
        change = wait_until(lambda: js(driver, f"(c => c && c.frame === {frame} && c.drawn ? c : null)"
                                               f"(fnetDashboard.runView.change)"), 60, f"frame {frame}'s change")
        measure = {"run": "live", "frame": previous, "other_frame": frame, "metric": "bottleneck", "dim": 1,
                   "force": "normal", "essential": "floor"}
        blocks = api.call("blocks.get", dict(measure, k=4))
        strip = lambda d: {k: v for k, v in d.items() if k != "seconds"}
        assert strip(change["blocks"]) == strip(blocks), (change["blocks"], blocks)
        distance = api.call("distance.get", dict(measure, explain=5))
        assert strip(change["distance"]) == strip(distance), (change["distance"], distance)
        before = api.call("network.get", {"run": "live", "frame": previous})
        after = api.call("network.get", {"run": "live", "frame": frame})
        assert change["drawn"]["changed"] == changed_contacts(before, after, "normal"), change["drawn"]["changed"]
        terms = distance.get("explain", [])
        placed = [t for t in terms if (t["b"] or t["a"]) and (t["b"] or t["a"])["birth_simplex"].get("positions")]
        assert [m["rank"] for m in change["drawn"]["marks"]] == [t["rank"] for t in placed], change["drawn"]["marks"]
        title = driver.find_element("id", "change-title").text
        assert f"frame {frame}" in title and f"frame {previous}" in title, title
        rows = driver.find_elements("css selector", "#terms tbody tr")
        assert len(rows) == max(1, len(terms)), (len(rows), len(terms))
        driver.execute_script("document.getElementById('change').scrollIntoView()")
        driver.save_screenshot(os.path.join(shots, "frame-change.png"))
        print(f"ok: clicking frame {frame} shows it against frame {previous}: {change['drawn']['changed']} contacts "
              f"changed, blocks.get's {len(blocks['cells'])} cells, distance.get's {len(terms)} explained terms")

        # An ensemble: its band is ensemble.series', live.
        ens = server.simd(ENSEMBLE, os.path.join(work, "ensemble.log"))
        wait_until(lambda: driver.find_elements("css selector", "tr[data-ensemble='ens']"), 300, "the ensemble's row")
        driver.find_element("css selector", "tr[data-ensemble='ens']").click()
        assert ens.wait(600) == 0, open(os.path.join(work, "ensemble.log")).read()
        for seed in (1, 2, 3):
            api.wait_for_frames(f"ens-s{seed}", 12)
        curve = api.call("ensemble.series", {"ensemble": "ens", "metric": "bottleneck", "dim": 1})
        keys = ["rho_lo", "rho_hi", "rho", "mean", "stderr", "n_runs", "n", "z"]
        expected = [{k: curve[k][i] for k in keys} for i in range(len(curve["rho_lo"]))]

        def band_matches():
            band = js(driver, "fnetDashboard.band()")
            return [{k: b[k] for k in keys} for b in band] == expected

        wait_until(band_matches, 30, f"the band to be ensemble.series' ({len(expected)} bins)")
        assert len(curve["runs"]) == 3, curve["runs"]
        time.sleep(0.5)
        driver.save_screenshot(os.path.join(shots, "ensemble.png"))
        print(f"ok: the ensemble's band is ensemble.series', {len(expected)} bins over {len(curve['runs'])} runs, "
              "filled in live")

        errors = console_errors(driver)
        assert not errors, errors
        print("ok: no console errors")
        return 0
    finally:
        if driver:
            close_browser(driver)
        server.stop()


if __name__ == "__main__":
    sys.exit(main())
