"""`boatsim view`: a bag and a running simulation drawn by Rerun, and the page in a browser.

The browser test opens the served page in headless Chromium (Debian's chromium and
chromium-driver, which `make test` installs) through Selenium, with SwiftShader's software
WebGL, and looks at the screenshot's pixels: the sea's blues, the hulls' colours and the
world's obstacles (ros/world.py's warm grey, which nothing else on the page is drawn in).
"""

import shutil
import socket
import subprocess
import sys
import time

import numpy as np
import pytest
import yaml
from support import ROOT, cli_run
from support import rrd_entities as _entities

MULTI = "scenarios/multi_boat.yaml"
#: The bag's world: MULTI's three boats and two obstacles in the camera's view, clear of the
#: boats' 5 s (a cylinder north-east of alpha, a pier beyond it).
WORLD = {"obstacles": [
    {"name": "tower", "type": "cylinder", "center": [10.0, 4.0], "radius": 2.0, "top": 4.0},
    {"name": "pier", "type": "polygon", "top": 2.0,
     "points": [[16.0, 6.0], [19.0, 6.0], [19.0, 14.0], [16.0, 14.0]]}]}
#: Their markers' entities: the cylinder, the pier's walls and its outline (ros/world.py).
OBSTACLES = {"/world/obstacles/obstacles/0", "/world/obstacles/obstacles/1",
             "/world/obstacles/obstacles/100001"}
#: rerun-sdk (the view extra; make test installs it) needs Python 3.11.
pytestmark = pytest.mark.skipif(sys.version_info < (3, 11), reason="rerun-sdk needs 3.11+")


@pytest.fixture(scope="module")
def bag(tmp_path_factory):
    """MULTI with :data:`WORLD`, 5 s recorded (the view is given MULTI: the same boats)."""
    folder = tmp_path_factory.mktemp("view")
    scenario, path = folder / "multi_world.yaml", folder / "bag"
    scenario.write_text(yaml.safe_dump({**yaml.safe_load((ROOT / MULTI).read_text()),
                                        "world": WORLD}))
    out = cli_run("run", str(scenario), "--fast", "--duration", "5", "--record", str(path))
    assert out.returncode == 0, out.stderr
    return path


def test_a_bag_is_drawn_boat_by_boat_on_its_sea(bag, tmp_path):
    out = cli_run("view", str(bag), "--scenario", MULTI, "--save", str(tmp_path / "v.rrd"))
    assert out.returncode == 0, out.stderr
    assert "of 3 boat(s)" in out.stderr
    drawn = _entities(tmp_path / "v.rrd")
    for boat in ("alpha", "bravo", "charlie"):
        assert {f"/world/{boat}", f"/world/{boat}/hull", f"/world/{boat}/name",
                f"/world/{boat}/forces/thrust", f"/world/paths/{boat}"} <= drawn, drawn
    assert {"/world/sea", "/world/focus"} <= drawn
    assert OBSTACLES <= drawn, drawn


def test_the_live_view_draws_the_running_simulation(boatsim, probe, tmp_path):
    from nav_msgs.msg import Odometry

    sim = boatsim("run")  # the default scenario, real time
    seen = []
    probe.node.create_subscription(Odometry, "/odom", seen.append, 10)
    probe.spin_until(lambda: seen, 60.0, "/odom")
    out = cli_run("view", "--save", str(tmp_path / "live.rrd"), "--duration", "2", timeout=90)
    assert out.returncode == 0, out.stderr
    assert "showing boat (root namespace)" in out.stderr
    drawn = _entities(tmp_path / "live.rrd")
    assert {"/world/boat", "/world/boat/hull", "/world/sea", "/world/focus"} <= drawn, drawn
    assert sim.stop() == 0


def test_a_bag_that_is_not_there_or_has_no_boats_exits_2(tmp_path):
    out = cli_run("view", str(tmp_path / "nothing"), "--save", str(tmp_path / "v.rrd"))
    assert out.returncode == 2 and "boatsim view: error:" in out.stderr
    assert "Traceback" not in out.stderr


def test_a_port_in_use_exits_2_naming_it(tmp_path):
    with socket.socket() as taken:
        taken.bind(("0.0.0.0", 0))
        taken.listen()
        port = taken.getsockname()[1]
        out = cli_run("view", "--grpc-port", str(port), timeout=60)
    assert out.returncode == 2, out.stderr
    assert f"port {port} is in use" in out.stderr and "--grpc-port" in out.stderr


def _listening(port: int) -> set[str]:
    """The addresses a TCP socket listens on at ``port`` (Linux: /proc/net/tcp, tcp6)."""
    found = set()
    for table in ("/proc/net/tcp", "/proc/net/tcp6"):
        with open(table) as f:
            for row in f.readlines()[1:]:
                local, state = row.split()[1], row.split()[3]
                address, hex_port = local.split(":")
                if state == "0A" and int(hex_port, 16) == port:
                    found.add(address)
    return found


def test_the_view_listens_on_this_machine_only_unless_told(bag, boatsim):
    """Before: its page and its Rerun server listened on every interface (0.0.0.0)."""
    loopback = "0100007F"  # 127.0.0.1 as /proc/net/tcp writes it
    for extra, expected in (((), {loopback}), (("--bind", "0.0.0.0"), {"00000000"})):
        web, grpc = _free_port(), _free_port()
        view = boatsim("view", str(bag), "--scenario", MULTI, "--web-port", str(web),
                       "--grpc-port", str(grpc), *extra, name="view")
        deadline = time.monotonic() + 60
        while "open http" not in view.output():
            assert view.proc.poll() is None and time.monotonic() < deadline, view.output()
            time.sleep(0.2)
        assert _listening(web) == expected and _listening(grpc) == expected
        assert view.stop() == 0
        assert not _listening(web) and not _listening(grpc)  # the server ended with it


def test_ctrl_c_in_the_terminal_ends_the_view_and_its_server_without_errors(bag, tmp_path):
    """A terminal's Ctrl-C signals the whole process group. Before: the Rerun server child died
    of it at once, and the view's last flush printed "ERROR ... transport error" and "gRPC
    connection severed" on exit 0."""
    import os
    import signal

    web, grpc = _free_port(), _free_port()
    log = tmp_path / "view.log"
    with open(log, "w") as out:
        view = subprocess.Popen([sys.executable, "-m", "boat_dynamics", "view", str(bag),
                                 "--scenario", MULTI, "--web-port", str(web), "--grpc-port",
                                 str(grpc)], stdout=out, stderr=subprocess.STDOUT,
                                start_new_session=True)  # its own group, as in a terminal
        try:
            deadline = time.monotonic() + 60
            while "open http" not in log.read_text():
                assert view.poll() is None and time.monotonic() < deadline, log.read_text()
                time.sleep(0.2)
            os.killpg(view.pid, signal.SIGINT)
            assert view.wait(timeout=30) == 0, log.read_text()
        finally:
            if view.poll() is None:
                os.killpg(view.pid, signal.SIGKILL)
                view.wait()
    text = log.read_text()
    assert "ERROR" not in text and "Traceback" not in text, text
    assert not _listening(web) and not _listening(grpc)  # the server ended with it


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _shares(png):
    """(share of sea-blue pixels, count of hull-orange ones, count of obstacle-grey ones) in the
    3-D view of a screenshot.

    The obstacles are ros/world.py's (140, 128, 115) walls and cylinders, shaded darker on
    their sides: a warm grey, r > g > b with r 1.1-1.4 times b. The page has no such pixel
    without them (0 of the 3-D view's, measured; the labels' greys are neutral or brighter,
    the hulls' edges on the sea redder), 3865 with :data:`WORLD`.
    """
    from PIL import Image

    a = np.asarray(Image.open(png).convert("RGB")).astype(int)[45:-40]  # no title, time bar
    r, g, b = a[..., 0], a[..., 1], a[..., 2]
    sea = (b > r + 40) & (b > g + 10) & (b > 90)
    orange = (r > 200) & (g > 80) & (g < 160) & (b < 90)  # alpha's hull, (232, 118, 36)
    grey = ((r < 170) & (b > 40) & (r > g) & (g > b) & (r - g < 20) & (10 * r > 11 * b)
            & (10 * r < 14 * b))
    return float(sea.mean()), int(orange.sum()), int(grey.sum())


def _browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    for program in ("/usr/bin/chromium", "/usr/bin/chromedriver"):
        assert shutil.which(program), (f"{program} is missing: `make test` installs Debian's "
                                       "chromium and chromium-driver")
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for flag in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-quic",
                 "--no-first-run", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--disable-dev-shm-usage",
                 "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                 "--window-size=1280,800", "--user-data-dir=/tmp/boatsim-test-chromium"):
        options.add_argument(flag)
    return webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)


def test_the_page_shows_the_boats_on_the_sea_in_a_headless_browser(bag, boatsim, tmp_path):
    """And the world: the bag's obstacles (/world/markers) drawn, counted by their colour."""
    web, grpc = _free_port(), _free_port()
    view = boatsim("view", str(bag), "--scenario", MULTI, "--web-port", str(web),
                   "--grpc-port", str(grpc), name="view")
    deadline = time.monotonic() + 60
    while "open http" not in view.output() or "boat(s) from" not in view.output():
        assert view.proc.poll() is None and time.monotonic() < deadline, view.output()
        time.sleep(0.2)
    url = view.output().split("open ")[1].split()[0]
    driver = _browser()
    shot = tmp_path / "view.png"
    try:
        driver.get(url)
        deadline = time.monotonic() + 120  # the viewer's wasm compiles in software
        while True:
            driver.save_screenshot(str(shot))
            sea, hull, world = _shares(shot)
            if (sea > 0.1 and hull > 30 and world > 1000) or time.monotonic() > deadline:
                break
            time.sleep(2.0)
    finally:
        driver.quit()
    print(f"screenshot: {shot} (sea {sea:.0%} of the view, {hull} hull pixels, {world} "
          "obstacle pixels)")
    assert sea > 0.1, f"the sea covers {sea:.1%} of the view ({shot})"
    assert hull > 30, f"{hull} pixels of alpha's orange hull ({shot})"
    assert world > 1000, f"{world} pixels of the obstacles' grey ({shot})"
    assert view.stop() == 0
