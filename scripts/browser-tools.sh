# Sourced by the browser checks (ci-viewer.sh, ci-exchange.sh): installs
# Debian's chromium, node and npm where missing, then prints their versions.
# CHROMIUM overrides the browser's path (default /usr/bin/chromium).
missing=()
[ -x "${CHROMIUM:-/usr/bin/chromium}" ] || missing+=(chromium)
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
"${CHROMIUM:-/usr/bin/chromium}" --version
echo "node $(node --version)"
