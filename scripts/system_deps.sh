#!/usr/bin/env bash
# The system programs the site tests and the PDF need, from Debian:
#   chromium       headless browser (browser test, `make pdf`), at /usr/bin/chromium
#   poppler-utils  pdftotext / pdfimages / pdffonts (the PDF test)
#   fonts-wqy-zenhei the Chinese of the glossary and references in the PDF (a TrueType
#                  CJK font: Chromium embeds it as a named font; Noto CJK, a CFF font,
#                  would be drawn as unnamed Type 3 glyphs)
#   bubblewrap     bwrap, the sandbox of each graded submission (`grade`)
#   nodejs, npm    npm fetches Pyodide; node runs it at build time to compile the
#                  in-browser site's bytecode (scripts/pyc_lite.py)
# Installed with apt-get when running as root (or with passwordless sudo);
# otherwise the script fails and says what to install.
set -euo pipefail

missing=()
if [[ -n "${CHROMIUM:-}" ]]; then
    [[ -x "$CHROMIUM" ]] || { echo "sysdeps: CHROMIUM=$CHROMIUM is not an executable" >&2; exit 1; }
else
    [[ -x /usr/bin/chromium ]] || command -v chromium >/dev/null 2>&1 || missing+=(chromium)
fi
command -v pdftotext >/dev/null 2>&1 && command -v pdfimages >/dev/null 2>&1 || missing+=(poppler-utils)
# (not `fc-list | grep -q`: grep stops at the first match, fc-list then dies of
# SIGPIPE, and under pipefail the font would count as missing)
fonts="$(fc-list 2>/dev/null || true)"
grep -q "WenQuanYi Zen Hei" <<<"$fonts" || missing+=(fonts-wqy-zenhei)
command -v bwrap >/dev/null 2>&1 || missing+=(bubblewrap)
command -v node >/dev/null 2>&1 || missing+=(nodejs)
command -v npm >/dev/null 2>&1 || missing+=(npm)

if ((${#missing[@]} == 0)); then
    exit 0
fi

if [[ "$(id -u)" -eq 0 ]]; then
    SUDO=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
    SUDO=(sudo -n)
else
    echo "sysdeps: missing ${missing[*]}: install them with" >&2
    echo "    sudo apt-get install ${missing[*]}" >&2
    echo "(or set CHROMIUM=/path/to/chromium for another Chromium build)" >&2
    exit 1
fi
echo "sysdeps: apt-get install ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" apt-get update -q
"${SUDO[@]}" apt-get install -y -q "${missing[@]}" </dev/null
