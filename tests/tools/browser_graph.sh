#!/usr/bin/env bash
# The editor in headless chromium (graph): a graph with fan-out built by clicking, its shell export run and compared with the preview byte for byte, any node previewed in 2D and in the standard scene, saved in a project and loaded back after a reload (tests/tools/browser.lib, cdp.py).
. "$(dirname "$0")/../lib.sh"
. "$(dirname "$0")/browser.lib"
browser graph
