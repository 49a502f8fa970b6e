#!/usr/bin/env python3
"""Makes a layerjkr wheel self-contained, as auditwheel repair does, from Debian's tools only
(ldd, patchelf, dpkg): every shared library the extension needs beyond glibc, libstdc++ and
libgcc is copied into layerjkr.libs/ with RUNPATH $ORIGIN, the extension gets RUNPATH
$ORIGIN/../layerjkr.libs, each bundled library's Debian copyright file is shipped beside it,
RECORD is rewritten, and the platform tag becomes manylinux_2_<glibc minor>_<arch> (the glibc the
wheel was built against is the oldest it needs).

    python3 tools/bundle_wheel.py dist/layerjkr-0.1.0-cp311-cp311-linux_x86_64.whl -o wheelhouse/

docs/python.md ("A wheel for any Linux") says what it guarantees and how it is tested.
"""
import argparse
import base64
import csv
import hashlib
import io
import os
import pathlib
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import zipfile

# The libraries every Linux with glibc has (the manylinux policy's list): never bundled.
SYSTEM = re.compile(r"^(linux-vdso|ld-linux[-\w.]*|libc|libm|libdl|librt|libpthread|libutil|libresolv|libnsl|"
                    r"libcrypt|libgcc_s|libstdc\+\+)\.so(\.\d+)*$")
LIBS = "layerjkr.libs"


def needed_libraries(extension):
    """(soname, resolved path) of every library ldd resolves for `extension`, transitively."""
    out = subprocess.run(["ldd", str(extension)], capture_output=True, text=True, check=True).stdout
    found = []
    for line in out.splitlines():
        m = re.match(r"\s*(\S+) => (\S+) \(0x", line)
        if m and not SYSTEM.match(m.group(1)):
            found.append((m.group(1), os.path.realpath(m.group(2))))
        elif "not found" in line:
            raise SystemExit("bundle_wheel: %s" % line.strip())
    return found


def copyright_of(path):
    """The Debian package owning `path` and its copyright file (None if dpkg does not know it)."""
    for candidate in (path, path.replace("/usr/lib/", "/lib/", 1), path.replace("/lib/", "/usr/lib/", 1)):
        r = subprocess.run(["dpkg", "-S", candidate], capture_output=True, text=True)
        if r.returncode == 0:
            package = r.stdout.split(":")[0].strip()
            doc = pathlib.Path("/usr/share/doc") / package / "copyright"
            return package, doc if doc.exists() else None
    return None, None


def record_line(root, path):
    data = path.read_bytes()
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return [path.relative_to(root).as_posix(), "sha256=" + digest, str(len(data))]


def bundle(wheel, out_dir):
    glibc = platform.libc_ver()[1]
    minor = glibc.split(".")[1]
    arch = platform.machine()
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        with zipfile.ZipFile(wheel) as z:
            z.extractall(root)
        extensions = sorted(root.glob("layerjkr/_core*.so"))
        if len(extensions) != 1:
            raise SystemExit("bundle_wheel: expected one layerjkr/_core*.so in %s" % wheel)
        libs = root / LIBS
        (libs / "licenses").mkdir(parents=True)
        notes = []
        for soname, path in needed_libraries(extensions[0]):
            shutil.copyfile(path, libs / soname)
            os.chmod(libs / soname, 0o755)
            subprocess.run(["patchelf", "--set-rpath", "$ORIGIN", str(libs / soname)], check=True)
            package, doc = copyright_of(path)
            if doc is not None:
                shutil.copyfile(doc, libs / "licenses" / (package + ".copyright"))
            notes.append("%s\t%s\t%s" % (soname, path, package or "(not from a Debian package)"))
        (libs / "licenses" / "BUNDLED.txt").write_text(
            "Libraries bundled in layerjkr.libs (soname, source path, Debian package); their copyright\n"
            "files are beside this one.\n\n" + "\n".join(notes) + "\n")
        subprocess.run(["patchelf", "--set-rpath", "$ORIGIN/../" + LIBS, str(extensions[0])], check=True)
        dist = next(root.glob("*.dist-info"))
        tag = "manylinux_2_%s_%s" % (minor, arch)
        wheel_file = dist / "WHEEL"
        wheel_file.write_text(re.sub(r"^(Tag: .*-)linux_\w+$", r"\g<1>" + tag, wheel_file.read_text(), flags=re.M))
        record = dist / "RECORD"
        rows = [record_line(root, p) for p in sorted(root.rglob("*")) if p.is_file() and p != record]
        rows.append([record.relative_to(root).as_posix(), "", ""])
        buffer = io.StringIO()
        csv.writer(buffer, lineterminator="\n").writerows(rows)
        record.write_text(buffer.getvalue())
        name = re.sub(r"linux_\w+\.whl$", tag + ".whl", pathlib.Path(wheel).name)
        out = pathlib.Path(out_dir) / name
        out.parent.mkdir(parents=True, exist_ok=True)
        with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
            for p in sorted(root.rglob("*")):
                if p.is_file():
                    z.write(p, p.relative_to(root).as_posix())
        return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("wheel")
    parser.add_argument("-o", "--out-dir", default="wheelhouse")
    args = parser.parse_args()
    print(bundle(args.wheel, args.out_dir))


if __name__ == "__main__":
    sys.exit(main())
