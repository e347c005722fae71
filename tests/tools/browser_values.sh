#!/usr/bin/env bash
# The editor in headless chromium (values): every palette, exact typed values, defaults kept, the modes' rows, an error that clears the preview (tests/tools/browser.lib, cdp.py).
. "$(dirname "$0")/../lib.sh"
. "$(dirname "$0")/browser.lib"
browser values
