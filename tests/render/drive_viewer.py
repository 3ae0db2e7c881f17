#!/usr/bin/python3
"""Drives sinew's HTML viewer in headless Chromium through chromedriver's WebDriver HTTP API (standard
library only): opens the page, checks that it plays, pauses it, scrubs to a frame, clicks a wire and checks
the pick, takes a screenshot, and checks that the page logged no error.

usage: drive_viewer.py PAGE.html SCREENSHOT.png WIRE_NAME
Exit status 0 when every check passed; the failed check is printed otherwise.
"""
import base64
import json
import os
import socket
import subprocess
import sys
import time
import urllib.request

CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class WebDriver:
    def __init__(self, port):
        self.base = f"http://127.0.0.1:{port}"
        self.session = None

    def call(self, method, path, body=None, timeout=60):
        data = None if body is None else json.dumps(body).encode()
        request = urllib.request.Request(self.base + path, data=data, method=method,
                                         headers={"Content-Type": "application/json"})
        try:
            with urllib.request.urlopen(request, timeout=timeout) as response:
                return json.loads(response.read() or b"{}").get("value")
        except urllib.error.HTTPError as e:
            raise RuntimeError(f"{method} {path}: {e.code} {e.read()[:500]!r}") from None

    def session_call(self, method, path, body=None):
        return self.call(method, f"/session/{self.session}{path}", body)

    def script(self, source, *args):
        return self.session_call("POST", "/execute/sync", {"script": source, "args": list(args)})


def check(condition, what):
    if not condition:
        raise AssertionError(what)
    print(f"ok: {what}")


def main(page, screenshot, wire):
    port = free_port()
    driver_process = subprocess.Popen([CHROMEDRIVER, f"--port={port}"], stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL)
    driver = WebDriver(port)
    try:
        for _ in range(100):
            try:
                if driver.call("GET", "/status", timeout=2).get("ready"):
                    break
            except (OSError, RuntimeError):
                pass
            time.sleep(0.1)
        options = {"binary": CHROMIUM,
                   "args": ["--headless=new", "--no-sandbox", "--disable-dev-shm-usage", "--use-angle=swiftshader",
                            "--enable-unsafe-swiftshader", "--window-size=1200,800"]}
        created = driver.call("POST", "/session", {"capabilities": {"alwaysMatch": {
            "goog:chromeOptions": options, "goog:loggingPrefs": {"browser": "ALL"}}}})
        driver.session = created["sessionId"]
        driver.session_call("POST", "/url", {"url": "file://" + os.path.abspath(page)})
        for _ in range(200):
            if driver.script("return typeof window.sinewViewer !== 'undefined';"):
                break
            time.sleep(0.1)
        check(driver.script("return typeof window.sinewViewer !== 'undefined';"), "the viewer started")
        frames = driver.script("return window.sinewViewer.frames;")

        state = driver.script("return window.sinewViewer.getState();")
        check(state["playing"], "it plays on opening")
        first = state["frame"]
        time.sleep(1.5)
        check(driver.script("return window.sinewViewer.getState().frame;") != first, "the frame advances while playing")
        button = driver.session_call("POST", "/element", {"using": "css selector", "value": "#play"})
        driver.session_call("POST", f"/element/{list(button.values())[0]}/click", {})
        check(not driver.script("return window.sinewViewer.getState().playing;"), "the play button pauses it")

        target = frames // 2
        driver.script("var s = document.getElementById('scrub'); s.value = arguments[0];"
                      "s.dispatchEvent(new Event('input'));", target)
        check(driver.script("return window.sinewViewer.getState().frame;") == target, f"scrubbing shows frame {target}")

        point = driver.script("return window.sinewViewer.screenPointOfWire(arguments[0]);", wire)
        x, y = int(round(point["x"])), int(round(point["y"]))
        driver.session_call("POST", "/actions", {"actions": [{"type": "pointer", "id": "mouse",
            "parameters": {"pointerType": "mouse"}, "actions": [
                {"type": "pointerMove", "duration": 0, "x": x, "y": y, "origin": "viewport"},
                {"type": "pointerDown", "button": 0}, {"type": "pointerUp", "button": 0}]}]})
        state = driver.script("return window.sinewViewer.getState();")
        check(state["picked"] == wire, f"a click at ({x}, {y}) picks wire '{wire}' (picked {state['picked']})")
        check(state["info"].startswith(wire + " ("), f"the panel names it: {state['info']}")
        time.sleep(0.3)

        with open(screenshot, "wb") as f:
            f.write(base64.b64decode(driver.session_call("GET", "/screenshot")))
        print(f"ok: screenshot {screenshot}")

        errors = driver.script("return window.sinewErrors;")
        try:
            errors += [e["message"] for e in driver.session_call("POST", "/se/log", {"type": "browser"})
                       if e.get("level") == "SEVERE"]
        except RuntimeError:
            pass  # a chromedriver without the log endpoint: the page's own record stands
        check(not errors, "no console errors" + ("" if not errors else f": {errors}"))
        return 0
    except (AssertionError, RuntimeError, OSError) as e:
        print(f"FAILED: {e}")
        return 1
    finally:
        if driver.session:
            try:
                driver.session_call("DELETE", "")
            except (RuntimeError, OSError):
                pass
        driver_process.terminate()
        driver_process.wait(timeout=10)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        raise SystemExit(__doc__)
    sys.exit(main(*sys.argv[1:]))
