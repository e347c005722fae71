#!/usr/bin/env bash
# The editor in headless chromium (project): a project saved as JSON, not replaced unless confirmed, loaded back after a reload (tests/tools/browser.lib, cdp.py).
. "$(dirname "$0")/../lib.sh"
. "$(dirname "$0")/browser.lib"
browser project
