"""The package's PEP 517 build backend: `pip install ./python` into any CPython 3.9+ environment.

It needs nothing from an index (pyproject.toml requires nothing), so it works offline: it compiles
_smql.cpp with the system's C++ compiler against this interpreter's headers, Debian's pybind11
headers (pybind11-dev) and libsmql, and zips the wheel itself. libsmql is found, in order, at
SMQL_PREFIX (an install prefix: include/smql.h, lib/libsmql.so), in the build tree beside the
package (../build, as `make` leaves it; SMQL_BUILD names another), or through pkg-config (`make
install` writes smql.pc). The extension records the library's folder as its run path.
"""
import base64
import csv
import hashlib
import io
import os
import pathlib
import re
import shlex
import subprocess
import sys
import sysconfig
import tarfile
import tempfile
import zipfile

HERE = pathlib.Path(__file__).resolve().parent.parent  # python/
NAME = "smql"


def _version():
    cmake = HERE.parent / "CMakeLists.txt"
    if cmake.exists():
        found = re.search(r"project\(smql VERSION ([0-9.]+)", cmake.read_text())
        if found:
            return found.group(1)
    return "0.0.0"


def _library():
    """(compile flags, link flags, library folder) for libsmql."""
    prefix = os.environ.get("SMQL_PREFIX")
    if prefix:
        prefix = pathlib.Path(prefix)
        libdir = next((d for d in (prefix / "lib", prefix / "lib64") if (d / "libsmql.so").exists()), prefix / "lib")
        return [f"-I{prefix / 'include'}"], [f"-L{libdir}", "-lsmql"], libdir
    build = pathlib.Path(os.environ.get("SMQL_BUILD", HERE.parent / "build"))
    built = next(iter(sorted(build.glob("drivers/c/libsmql.so*"))), None) if build.exists() else None
    if built:
        libdir = built.parent
        return [f"-I{HERE.parent / 'drivers' / 'c'}"], [f"-L{libdir}", "-lsmql"], libdir
    try:
        cflags = subprocess.run(["pkg-config", "--cflags", "smql"], check=True, capture_output=True, text=True)
        libs = subprocess.run(["pkg-config", "--libs", "smql"], check=True, capture_output=True, text=True)
        libdir = subprocess.run(["pkg-config", "--variable=libdir", "smql"], check=True, capture_output=True,
                                text=True)
    except (OSError, subprocess.CalledProcessError):
        raise SystemExit("smql: libsmql not found: build the project (make), or `make install` it, or set "
                         "SMQL_PREFIX to an install prefix or SMQL_BUILD to a build folder")
    return shlex.split(cflags.stdout), shlex.split(libs.stdout), pathlib.Path(libdir.stdout.strip())


def _compile(out_dir):
    """Builds _smql for this interpreter into out_dir; returns its file name."""
    suffix = sysconfig.get_config_var("EXT_SUFFIX")
    target = pathlib.Path(out_dir) / f"_smql{suffix}"
    cflags, libs, libdir = _library()
    compiler = os.environ.get("CXX", "c++")
    command = [compiler, "-O2", "-std=c++20", "-shared", "-fPIC", "-fvisibility=hidden",
               f"-I{sysconfig.get_paths()['include']}", *cflags, str(HERE / "_smql.cpp"), "-o", str(target),
               *libs, f"-Wl,-rpath,{libdir}"]
    print("smql:", " ".join(command), file=sys.stderr)
    subprocess.run(command, check=True)
    return target


def _tag():
    interpreter = f"cp{sys.version_info.major}{sys.version_info.minor}"
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    return f"{interpreter}-{interpreter}-{platform}"


def _metadata(version):
    return (f"Metadata-Version: 2.1\nName: {NAME}\nVersion: {version}\n"
            "Summary: An embedded spatial memory engine (PEP 249 over its C API)\n"
            "Requires-Python: >=3.9\nProvides-Extra: numpy\nRequires-Dist: numpy; extra == \"numpy\"\n")


def _wheel(wheel_directory):
    version = _version()
    tag = _tag()
    dist_info = f"{NAME}-{version}.dist-info"
    files = {}  # path in the wheel -> bytes
    with tempfile.TemporaryDirectory() as work:
        extension = _compile(work)
        files[f"{NAME}/{extension.name}"] = extension.read_bytes()
    for source in sorted((HERE / NAME).glob("*.py")):
        files[f"{NAME}/{source.name}"] = source.read_bytes()
    files[f"{dist_info}/METADATA"] = _metadata(version).encode()
    files[f"{dist_info}/WHEEL"] = (f"Wheel-Version: 1.0\nGenerator: smql_build\nRoot-Is-Purelib: false\n"
                                   f"Tag: {tag}\n").encode()
    record = io.StringIO()
    writer = csv.writer(record, lineterminator="\n")
    for path, data in files.items():
        digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
        writer.writerow([path, f"sha256={digest}", len(data)])
    writer.writerow([f"{dist_info}/RECORD", "", ""])
    files[f"{dist_info}/RECORD"] = record.getvalue().encode()
    name = f"{NAME}-{version}-{tag}.whl"
    with zipfile.ZipFile(pathlib.Path(wheel_directory) / name, "w", zipfile.ZIP_DEFLATED) as wheel:
        for path, data in files.items():
            wheel.writestr(path, data)
    return name


# ---- PEP 517 hooks ------------------------------------------------------------------------------

def get_requires_for_build_wheel(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    return _wheel(wheel_directory)


def build_sdist(sdist_directory, config_settings=None):
    """The package's sources: pyproject.toml, the backend, _smql.cpp and smql/*.py."""
    base = f"{NAME}-{_version()}"
    name = f"{base}.tar.gz"
    with tarfile.open(pathlib.Path(sdist_directory) / name, "w:gz") as sdist:
        for path in ["pyproject.toml", "_smql.cpp", "backend/smql_build.py",
                     *(f"{NAME}/{p.name}" for p in sorted((HERE / NAME).glob("*.py")))]:
            sdist.add(HERE / path, arcname=f"{base}/{path}")
        info = tarfile.TarInfo(f"{base}/PKG-INFO")
        data = _metadata(_version()).encode()
        info.size = len(data)
        sdist.addfile(info, io.BytesIO(data))
    return name
