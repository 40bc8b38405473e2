# Sourced by the GPU host scripts: GLVND from .gl/ when the host lacks it.
if ! ldconfig -p | grep -q libEGL.so.1 && ls .gl/*.deb >/dev/null 2>&1; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
