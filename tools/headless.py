"""Headless Chromium with the network off, shared by the docs check and the viewer check.

A page is loaded from file:// with every host name resolving nowhere and every request sent to a
proxy that is not there, so a page that works here works on a machine with no network.
"""
import shutil
import subprocess

BROWSERS = ("chromium", "chromium-browser")


def find_browser():
    """The path of Chromium, or None when it is not installed."""
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    return None


def run(browser, page, profile, extra, fragment="", budget_ms=None, timeout=300):
    """Runs Chromium on page#fragment with its own profile folder and returns its stdout. With
    budget_ms, timers run ahead for that much page time (--virtual-time-budget); without, the
    page's clock is the wall's. Raises RuntimeError on a failed run, naming Chromium's status."""
    budget = [f"--virtual-time-budget={budget_ms}"] if budget_ms is not None else []
    cmd = [browser, "--headless", "--no-sandbox", "--no-first-run", "--disable-gpu", "--enable-unsafe-swiftshader",
           "--host-resolver-rules=MAP * ~NOTFOUND", "--proxy-server=http://127.0.0.1:9",
           "--disable-background-networking", "--disable-component-update", "--disable-sync",
           "--disable-default-apps", "--disable-domain-reliability", f"--user-data-dir={profile}",
           *budget, *extra, page.resolve().as_uri() + fragment]
    result = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if result.returncode != 0:
        raise RuntimeError(f"chromium failed (status {result.returncode}): {result.stderr.strip()[-300:]}")
    return result.stdout
