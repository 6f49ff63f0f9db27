"""The dashboard in headless Chromium (label browser): the page loads without console errors and
draws the footsteps, the forward key walks the robot, the stop button stops it, the camera panel
shows an image. Each test saves a screenshot (docs/dashboard.md shows them)."""

import os
import shutil

import pytest

selenium = pytest.importorskip("selenium", reason="python3-selenium (scripts/setup.sh)")
from selenium import webdriver  # noqa: E402
from selenium.webdriver.chrome.service import Service  # noqa: E402
from selenium.webdriver.common.by import By  # noqa: E402
from selenium.webdriver.common.keys import Keys  # noqa: E402
from selenium.webdriver.support.ui import WebDriverWait  # noqa: E402


@pytest.fixture
def browser():
    for program in ("chromium", "chromedriver"):
        if shutil.which(program) is None:
            pytest.fail(f"{program} is missing: install chromium and chromium-driver "
                        "(scripts/setup.sh)")
    options = webdriver.ChromeOptions()
    for argument in ("--headless=new", "--no-sandbox", "--disable-gpu", "--window-size=1280,1100",
                     "--disable-dev-shm-usage"):
        options.add_argument(argument)
    options.binary_location = shutil.which("chromium")
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    service = Service(executable_path=shutil.which("chromedriver"))
    driver = webdriver.Chrome(options=options, service=service)
    driver.set_page_load_timeout(30)
    yield driver
    driver.quit()


def console_errors(driver):
    return [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]


def open_page(browser, dashboard):
    browser.get(dashboard.url + "/")
    WebDriverWait(browser, 30).until(
        lambda d: d.execute_script("return window.dashboard && window.dashboard.framesDrawn") > 2)


def test_the_page_loads_without_errors_and_draws_the_footsteps(browser, dashboard, screenshots):
    open_page(browser, dashboard)
    assert browser.title == "walkgen dashboard"
    drawn = browser.execute_script("return window.dashboard.footstepsDrawn")
    assert drawn == len(dashboard.state()["footsteps"]) and drawn >= 1
    # the canvas has footstep blue in it (the dashed outlines, #1565c0)
    blue = browser.execute_script("""
        const c = document.getElementById('topview'), g = c.getContext('2d');
        const d = g.getImageData(0, 0, c.width, c.height).data; let n = 0;
        for (let i = 0; i < d.length; i += 4)
          if (Math.abs(d[i] - 0x15) < 30 && Math.abs(d[i+1] - 0x65) < 30 && Math.abs(d[i+2] - 0xc0) < 30) n++;
        return n;""")
    assert blue > 50
    assert "walking" in browser.find_element(By.ID, "status").text
    browser.save_screenshot(os.path.join(screenshots, "dashboard_page.png"))
    assert console_errors(browser) == []


def test_the_forward_key_walks_the_robot_forward(browser, dashboard, screenshots):
    open_page(browser, dashboard)
    start = dashboard.state()["com"][0]
    body = browser.find_element(By.TAG_NAME, "body")
    for _ in range(6):  # 6 x 0.005 m/s
        body.send_keys(Keys.ARROW_UP)
    s = dashboard.wait(lambda s: abs(s["command"][0] - 0.03) < 1e-9, timeout=10)
    assert s["command"][1:] == [0.0, 0.0]
    dashboard.wait(lambda s: s["com"][0] > start + 0.05, timeout=60)
    assert browser.find_element(By.ID, "cmd-vx").text == "0.0300"
    browser.save_screenshot(os.path.join(screenshots, "dashboard_walking.png"))
    assert console_errors(browser) == []


def test_the_stop_button_stops_the_robot(browser, dashboard, screenshots):
    open_page(browser, dashboard)
    body = browser.find_element(By.TAG_NAME, "body")
    for _ in range(4):
        body.send_keys("w")
    dashboard.wait(lambda s: s["command"][0] > 0.0199, timeout=10)
    browser.find_element(By.ID, "btn-stop").click()
    stopped = dashboard.wait(lambda s: s["mode"] == "stopped", timeout=60)
    assert stopped["command"] == [0.0, 0.0, 0.0]
    WebDriverWait(browser, 10).until(
        lambda d: "stopped" in d.find_element(By.ID, "status").text)
    browser.save_screenshot(os.path.join(screenshots, "dashboard_stopped.png"))
    assert console_errors(browser) == []


def test_the_camera_panel_shows_the_cameras_image(browser, dashboard, screenshots):
    open_page(browser, dashboard)
    WebDriverWait(browser, 20).until(lambda d: d.execute_script(
        "const i = document.getElementById('camera-rgb'); return i.complete && i.naturalWidth > 0"))
    size = browser.execute_script(
        "const i = document.getElementById('camera-rgb'); return [i.naturalWidth, i.naturalHeight]")
    assert size[0] >= 160 and size[1] >= 120
    depth = browser.execute_script("return document.getElementById('camera-depth').naturalWidth")
    assert depth == size[0]
    browser.save_screenshot(os.path.join(screenshots, "dashboard_camera.png"))
    assert console_errors(browser) == []


def test_the_training_view_plots_a_runs_log(browser, training_dashboard, training_run,
                                            screenshots):
    from conftest import ppo_row
    open_page(browser, training_dashboard)
    WebDriverWait(browser, 20).until(lambda d: d.execute_script(
        "return window.dashboard.trainingRows") == 5)
    assert browser.find_element(By.ID, "training-panel").is_displayed()
    with open(training_run / "learning_nmpc.csv", "a") as f:  # plotted live
        f.write(ppo_row(6))
    WebDriverWait(browser, 20).until(lambda d: d.execute_script(
        "return window.dashboard.trainingRows") == 6)
    inked = browser.execute_script("""
        const c = document.getElementById('plot-success'), g = c.getContext('2d');
        const d = g.getImageData(0, 20, c.width, c.height - 20).data; let n = 0;
        for (let i = 0; i < d.length; i += 4) if (d[i + 3] > 0) n++;
        return n;""")
    assert inked > 100  # the success-rate curve is drawn
    browser.execute_script("document.getElementById('training-panel').scrollIntoView()")
    browser.save_screenshot(os.path.join(screenshots, "dashboard_training.png"))
    assert console_errors(browser) == []
