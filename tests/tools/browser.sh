#!/usr/bin/env bash
# The editor in headless chromium (basic): picks noise, moves a slider, adds a palette step, saves the map and runs the page's command line (tests/tools/browser.lib, cdp.py).
. "$(dirname "$0")/../lib.sh"
. "$(dirname "$0")/browser.lib"
browser basic
