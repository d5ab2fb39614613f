# Sourced by the install scripts: apt_install NAME MODE PACKAGE...
#   Installs the missing packages with apt-get (sudo when not root); does
#   nothing when all are present.  MODE --check only reports what is missing
#   (status 1 if anything is).  NAME prefixes the messages.
apt_install() {
  local name=$1 mode=$2
  shift 2
  local missing=() p
  for p in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
      missing+=("$p")
    fi
  done
  if [ "$mode" = "--check" ]; then
    if [ ${#missing[@]} -eq 0 ]; then echo "$name: all packages present"; return 0; fi
    echo "$name: missing: ${missing[*]}"
    return 1
  fi
  if [ ${#missing[@]} -eq 0 ]; then
    echo "$name: all $# packages already installed"
    return 0
  fi
  echo "$name: installing ${missing[*]}"
  local sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
}
