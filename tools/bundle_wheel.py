#!/usr/bin/env python3
"""Makes a layerjkr wheel self-contained, as auditwheel repair does, from Debian's tools only
(ldd, patchelf, readelf, dpkg): every shared library the extension needs beyond glibc, libstdc++
and libgcc is copied into layerjkr.libs/ under a name carrying its content's hash (libgsl.so.27 ->
libgsl-1a2b3c4d.so.27, its SONAME and every NEEDED entry rewritten to match, so a copy of the same
library that another package loaded first cannot stand in for it, nor this one for that), with
RUNPATH $ORIGIN; the extension gets RUNPATH $ORIGIN/../layerjkr.libs; each bundled library's
Debian copyright file is shipped beside it, and BUNDLED.txt names its package, version and where
its sources are; RECORD is rewritten; the platform tag becomes manylinux_2_<minor>_<arch> for the
newest GLIBC symbol version any of the wheel's objects needs (not the build machine's glibc).

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


def hashed_name(soname, path):
    """libgsl.so.27 -> libgsl-<first 8 hex digits of the file's SHA-256>.so.27, as auditwheel names them."""
    digest = hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()[:8]
    stem, dot_so, rest = soname.partition(".so")
    return "%s-%s%s%s" % (stem, digest, dot_so, rest)


def needed_entries(path):
    return subprocess.run(["patchelf", "--print-needed", str(path)], capture_output=True, text=True,
                          check=True).stdout.split()


def newest_version(paths, prefix):
    """The newest symbol version `prefix`X.Y[.Z] (GLIBC_, GLIBCXX_) that any of `paths` needs, as a
    tuple of ints, from readelf's version-needs sections."""
    newest = (0,)
    for path in paths:
        out = subprocess.run(["readelf", "-V", "--wide", str(path)], capture_output=True, text=True, check=True).stdout
        for version in re.findall(r"Name: %s([0-9.]+)" % re.escape(prefix), out):
            newest = max(newest, tuple(int(x) for x in version.split(".")))
    return newest


def package_facts(package):
    """(version, source package) of an installed Debian package."""
    r = subprocess.run(["dpkg-query", "-W", "-f=${Version}\t${source:Package}", package], capture_output=True,
                       text=True)
    if r.returncode != 0:
        return "?", package
    version, source = r.stdout.split("\t")
    return version, source or package


def record_line(root, path):
    data = path.read_bytes()
    digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
    return [path.relative_to(root).as_posix(), "sha256=" + digest, str(len(data))]


def bundle(wheel, out_dir):
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
        notes, renamed = [], {}
        for soname, path in needed_libraries(extensions[0]):
            name = hashed_name(soname, path)
            renamed[soname] = name
            shutil.copyfile(path, libs / name)
            os.chmod(libs / name, 0o755)
            # Two calls: Debian 12's patchelf (0.14) given both in one wrote the RUNPATH into the SONAME.
            subprocess.run(["patchelf", "--set-soname", name, str(libs / name)], check=True)
            subprocess.run(["patchelf", "--set-rpath", "$ORIGIN", str(libs / name)], check=True)
            package, doc = copyright_of(path)
            if doc is not None:
                shutil.copyfile(doc, libs / "licenses" / (package + ".copyright"))
            version, source = package_facts(package) if package else ("?", None)
            where = ("https://sources.debian.org/src/%s/%s/ (apt-get source %s=%s)" % (source, version, source, version)
                     if source else "(not from a Debian package)")
            notes.append("%s\t%s\t%s\t%s\t%s\t%s" % (name, soname, path, package or "-", version, where))
        # Every object names its bundled dependencies by their new names.
        for obj in [extensions[0]] + sorted(libs.glob("*.so*")):
            pairs = [(old, renamed[old]) for old in needed_entries(obj) if old in renamed]
            if pairs:
                args = ["patchelf"]
                for old, new in pairs:
                    args += ["--replace-needed", old, new]
                subprocess.run(args + [str(obj)], check=True)
        (libs / "licenses" / "BUNDLED.txt").write_text(
            "Libraries bundled in layerjkr.libs: the bundled name (the original soname with a hash of its\n"
            "content), the original soname, the path it was copied from, its Debian package and version, and\n"
            "where that version's sources are (the GPL and LGPL libraries among them - GSL, glog's and\n"
            "SuiteSparse's parts, libgfortran - are offered in source form there, as their licences ask).\n"
            "Their copyright files are beside this one.\n\n" + "\n".join(notes) + "\n")
        subprocess.run(["patchelf", "--set-rpath", "$ORIGIN/../" + LIBS, str(extensions[0])], check=True)
        objects = [extensions[0]] + sorted(libs.glob("*.so*"))
        glibc = newest_version(objects, "GLIBC_")
        if len(glibc) < 2 or glibc[0] != 2:
            raise SystemExit("bundle_wheel: cannot tell the newest GLIBC version the wheel needs (%s)" % (glibc,))
        dist = next(root.glob("*.dist-info"))
        tag = "manylinux_2_%d_%s" % (glibc[1], arch)
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
        glibcxx = newest_version(objects, "GLIBCXX_")
        print("bundle_wheel: %d libraries bundled; newest GLIBC_%s, GLIBCXX_%s needed" % (
            len(renamed), ".".join(map(str, glibc)), ".".join(map(str, glibcxx))), file=sys.stderr)
        return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("wheel")
    parser.add_argument("-o", "--out-dir", default="wheelhouse")
    args = parser.parse_args()
    print(bundle(args.wheel, args.out_dir))


if __name__ == "__main__":
    sys.exit(main())
