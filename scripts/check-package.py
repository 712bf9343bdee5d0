#!/usr/bin/env python3
"""Checks a Yak package folder laid out by scripts/package.sh (make package).

Usage: check-package.py FOLDER

The folder must hold exactly: manifest.yml, icon.png, TilePattern.Grasshopper.gha and
TilePattern.dll (both .NET assemblies, the .gha referencing TilePattern), and
runtimes/<rid>/native/ with the native library named as that platform names it
(tilepattern.dll, libtilepattern.dylib, libtilepattern.so) and built for it (PE, Mach-O or
ELF header). The manifest must have Yak's required fields (name, version, authors,
description), the version of Cargo.toml (and of grasshopper/TilePatternInfo.cs), no
placeholder url, keywords, and an icon that exists. An ELF library must need no COIN-OR
library (it links them statically). Prints one line per problem and exits 1 if any.
"""

import re
import struct
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
#: Shared COIN-OR libraries the native library must not need (it links them statically).
COIN_OR = re.compile(r"lib(Cbc|CbcSolver|Clp|ClpSolver|CoinUtils|Cgl|Osi|OsiClp|OsiCbc|OsiCommonTests)\b")
#: rid prefix -> (library file name, expected binary format)
PLATFORMS = {
    "win-": ("tilepattern.dll", "PE"),
    "osx-": ("libtilepattern.dylib", "Mach-O"),
    "linux-": ("libtilepattern.so", "ELF"),
}
#: rid suffix -> machine names accepted for it
MACHINES = {
    "x64": {"PE": {0x8664}, "ELF": {62}, "Mach-O": {0x01000007}},
    "arm64": {"PE": {0xAA64}, "ELF": {183}, "Mach-O": {0x0100000C}},
}


def parse_manifest(text):
    """The manifest's top-level scalars and lists (the YAML subset manifest.yml uses)."""
    fields, key = {}, None
    for raw in text.splitlines():
        line = raw.rstrip()
        if not line or line.lstrip().startswith("#") or line == "---":
            continue
        if line.startswith("- ") and key is not None:
            if not isinstance(fields[key], list):
                fields[key] = []
            fields[key].append(line[2:].strip())
        elif not line.startswith(" "):
            key, _, value = line.partition(":")
            key, value = key.strip(), value.strip()
            fields[key] = [] if value == "" else ("" if value == ">" else value)
        elif key is not None:
            # A folded scalar (description: >) continues on indented lines.
            previous = fields[key]
            fields[key] = (previous + " " if previous else "") + line.strip() if isinstance(previous, str) else previous
    return fields


def cargo_version():
    text = (ROOT / "Cargo.toml").read_text(encoding="utf-8")
    package = re.search(r"^\[package\]\n(.*?)(?=^\[|\Z)", text, re.S | re.M).group(1)
    return re.search(r'^version\s*=\s*"([^"]*)"', package, re.M).group(1)


def binary_format(path):
    """(format, machine) of a native library, from its header."""
    head = path.read_bytes()[:4096]
    if head[:4] == b"\x7fELF":
        little = head[5] == 1
        return "ELF", struct.unpack("<H" if little else ">H", head[18:20])[0]
    if head[:2] == b"MZ":
        offset = struct.unpack("<I", head[0x3C:0x40])[0]
        data = path.read_bytes()[offset : offset + 6]
        if data[:4] == b"PE\0\0":
            return "PE", struct.unpack("<H", data[4:6])[0]
    if head[:4] in (b"\xcf\xfa\xed\xfe", b"\xce\xfa\xed\xfe"):
        return "Mach-O", struct.unpack("<i", head[4:8])[0]
    if head[:4] in (b"\xca\xfe\xba\xbe",):
        # A universal (fat) binary: every architecture inside.
        count = struct.unpack(">I", head[4:8])[0]
        return "Mach-O", {struct.unpack(">i", head[8 + 20 * i : 12 + 20 * i])[0] for i in range(count)}
    return None, None


def is_dotnet_assembly(path):
    """A PE file with a CLI header (data directory 14 non-empty)."""
    data = path.read_bytes()
    if data[:2] != b"MZ":
        return False
    pe = struct.unpack("<I", data[0x3C:0x40])[0]
    if data[pe : pe + 4] != b"PE\0\0":
        return False
    optional = pe + 24
    magic = struct.unpack("<H", data[optional : optional + 2])[0]
    directories = optional + (96 if magic == 0x10B else 112)
    rva, size = struct.unpack("<II", data[directories + 14 * 8 : directories + 15 * 8])
    return rva != 0 and size != 0


def check(folder):
    problems = []
    folder = Path(folder)
    if not folder.is_dir():
        return ["%s is not a folder" % folder]

    expected = {"manifest.yml", "icon.png", "TilePattern.Grasshopper.gha", "TilePattern.dll"}
    present = {p.name for p in folder.iterdir() if p.is_file()}
    for name in sorted(expected - present):
        problems.append("%s is missing" % name)
    for name in sorted(present - expected):
        problems.append("%s does not belong in the package" % name)
    for p in folder.iterdir():
        if p.is_dir() and p.name != "runtimes":
            problems.append("folder %s/ does not belong in the package" % p.name)

    for name in ("TilePattern.Grasshopper.gha", "TilePattern.dll"):
        if (folder / name).is_file() and not is_dotnet_assembly(folder / name):
            problems.append("%s is not a .NET assembly" % name)
    gha = folder / "TilePattern.Grasshopper.gha"
    if gha.is_file() and b"TilePattern" not in gha.read_bytes().replace(b"TilePattern.Grasshopper", b""):
        problems.append("TilePattern.Grasshopper.gha does not reference the wrapper TilePattern")

    # The native libraries.
    runtimes = folder / "runtimes"
    rids = sorted(p.name for p in runtimes.iterdir() if p.is_dir()) if runtimes.is_dir() else []
    if not rids:
        problems.append("runtimes/<rid>/native/ holds no native library")
    for rid in rids:
        prefix = next((p for p in PLATFORMS if rid.startswith(p)), None)
        arch = rid.split("-", 1)[1] if "-" in rid else ""
        if prefix is None or arch not in MACHINES:
            problems.append("runtimes/%s: unknown rid (win-x64, win-arm64, osx-x64, osx-arm64, linux-x64, linux-arm64)" % rid)
            continue
        name, fmt = PLATFORMS[prefix]
        native = runtimes / rid / "native"
        files = sorted(p.name for p in native.iterdir()) if native.is_dir() else []
        if files != [name]:
            problems.append("runtimes/%s/native/ holds %s, expected exactly %s" % (rid, files or "nothing", name))
            continue
        found, machine = binary_format(native / name)
        machines = machine if isinstance(machine, set) else {machine}
        if found != fmt or not machines & MACHINES[arch][fmt]:
            problems.append("runtimes/%s/native/%s is not a %s library for %s (found %s, machine %s)" % (rid, name, fmt, arch, found, machine))
            continue
        if fmt == "ELF":
            try:
                dynamic = subprocess.run(["readelf", "-d", str(native / name)], capture_output=True, text=True, check=True).stdout
            except (OSError, subprocess.CalledProcessError) as e:
                problems.append("readelf -d %s failed: %s" % (name, e))
                continue
            needed = re.findall(r"\(NEEDED\)\s+Shared library: \[([^\]]+)\]", dynamic)
            coin = [n for n in needed if COIN_OR.match(n)]
            if coin:
                problems.append("runtimes/%s/native/%s needs COIN-OR libraries %s: build it with the static-coin feature" % (rid, name, ", ".join(coin)))

    # The manifest.
    manifest = folder / "manifest.yml"
    if manifest.is_file():
        fields = parse_manifest(manifest.read_text(encoding="utf-8"))
        for key in ("name", "version", "authors", "description"):
            if not fields.get(key):
                problems.append("manifest.yml: %s is missing or empty" % key)
        version = cargo_version()
        if fields.get("version") != version:
            problems.append("manifest.yml: version %s, Cargo.toml has %s" % (fields.get("version"), version))
        if fields.get("name") and not re.fullmatch(r"[a-z0-9][a-z0-9_-]*", fields["name"]):
            problems.append("manifest.yml: name %r is not a Yak package name (lower case, digits, - and _)" % fields["name"])
        url = fields.get("url")
        if url is not None and not re.fullmatch(r"https?://[^/\s]+/\S+", url):
            problems.append("manifest.yml: url %r is a placeholder or not a page's address" % url)
        if not isinstance(fields.get("keywords"), list) or not fields["keywords"]:
            problems.append("manifest.yml: keywords are missing")
        icon = fields.get("icon")
        if icon and not (folder / icon).is_file():
            problems.append("manifest.yml: icon %s is not in the package" % icon)
        # One version everywhere: the plug-in's own says the same.
        info = (ROOT / "grasshopper" / "TilePatternInfo.cs").read_text(encoding="utf-8")
        m = re.search(r'Version\s*\{\s*get\s*\{\s*return\s*"([^"]+)"', info)
        if not m or m.group(1) != version:
            problems.append("grasshopper/TilePatternInfo.cs: Version %s, Cargo.toml has %s" % (m.group(1) if m else "missing", version))
    return problems


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    problems = check(sys.argv[1])
    for problem in problems:
        print("check-package: " + problem)
    if problems:
        sys.exit(1)
    print("check-package: %s is complete" % sys.argv[1])


if __name__ == "__main__":
    main()
