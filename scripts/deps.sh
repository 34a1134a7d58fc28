# Sourced by the scripts: installs the Debian packages gdcontact needs, once (idempotent).
# Usage: install_packages pkg...   — installs only the missing ones (needs root, or sudo).
install_packages() {
    local missing=()
    for package in "$@"; do
        dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
    done
    [ ${#missing[@]} -eq 0 ] && return 0
    echo "Installing Debian packages: ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
}

# Packages needed to build the library alone (the lean build: GDCONTACT_BUILD_TESTS/SAMPLES=OFF).
LIBRARY_PACKAGES=(build-essential cmake pkg-config libeigen3-dev libqhull-dev libode-dev)
# Packages needed to build the library, samples, viewer and tests, and to run the viewer's tests
# headless (Xvfb with Mesa's software OpenGL).
BUILD_PACKAGES=("${LIBRARY_PACKAGES[@]}" libccd-dev catch2
                libglfw3-dev libimgui-dev libstb-dev libgl-dev libtinyobjloader-dev xvfb xauth libgl1-mesa-dri
                python3-matplotlib python3-pil)
