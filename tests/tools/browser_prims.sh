#!/usr/bin/env bash
# The editor in headless chromium (prims): every primitive of the registry picked with its defaults: a non-blank preview, no error (tests/tools/browser.lib, cdp.py).
. "$(dirname "$0")/../lib.sh"
. "$(dirname "$0")/browser.lib"
browser prims
