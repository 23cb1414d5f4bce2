"""Prints where this interpreter looks for packages installed under a prefix, relative to it: the
platlib of its default installation scheme, for CMake's LIDAR_SGM_INSTALL_PYTHONDIR.

Debian's python3: its default scheme is posix_local, {platbase}/local/lib/python3.X/dist-packages,
so that `pip install` as root, with platbase /usr, lands in /usr/local. For an installation prefix
(CMake's /usr/local by default) that "local" is the prefix's own: the answer is
lib/python3.X/dist-packages, which Debian's python3 searches under /usr/local and /usr. Elsewhere
(python.org's or pyenv's builds: lib/python3.X/site-packages; a virtual environment: the same
under it) the scheme's platlib is the answer as it is.
"""
import os
import sysconfig


def default_scheme():
    if hasattr(sysconfig, "get_default_scheme"):  # Python >= 3.10
        return sysconfig.get_default_scheme()
    return sysconfig._get_default_scheme()  # 3.7 - 3.9: the same, not yet public


def install_dir():
    scheme = default_scheme()
    prefix = os.path.join(os.sep, "prefix")
    platlib = sysconfig.get_path("platlib", scheme, vars={"base": prefix, "platbase": prefix})
    relative = os.path.relpath(platlib, prefix)
    local = "local" + os.sep
    if scheme == "posix_local" and relative.startswith(local):
        relative = relative[len(local):]
    return relative.replace(os.sep, "/")


if __name__ == "__main__":
    print(install_dir())
