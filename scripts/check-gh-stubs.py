#!/usr/bin/env python3
"""Checks the RhinoCommon and Grasshopper reference stubs in grasshopper/stubs/ member by member.

The stubs are C# files compiled into RhinoCommon.dll and Grasshopper.dll (target/gh/); the
Grasshopper components compile against them. This script reads what those assemblies declare
(a JSON-lines dump made by grasshopper/stubs/tools/DumpApi.cs from the compiled assemblies,
not from the C# text) and compares every type and member with the type stubs that McNeel's
tools generated from the real assemblies and published on PyPI:

  8.x  rhino-stubs-typed / grasshopper-stubs-typed  (RhinoCommon and Grasshopper 8)
  7.x  Rhino-stubs / Grasshopper-stubs               (RhinoCommon and Grasshopper 7)

A public member must be in both, with the same name, parameter count and types (ref and out
parameters as the stubs show them: in the returned tuple), return type, static or instance,
and for properties the getter and (when the stub has one) the setter. Enum members must have
the same numeric values; base types must be among the published type's bases.

What the published stubs cannot show is checked against a ledger instead
(grasshopper/stubs/ledger.txt, one line per member, written from the SDK documentation):
protected members, nested and generic types (the published stubs leave them out), and the
virtual / abstract / override modifiers (the stubs do not record them). Every such member of
the compiled stubs must have a ledger line with exactly its signature, and every ledger line
must match a stub member. The summary says how many members each source proved.

Usage: check-gh-stubs.py DUMP.jsonl SITE_PACKAGES LEDGER
Exit code 0 when everything matches, 1 with one line per mismatch otherwise.
"""
import ast
import json
import keyword
import os
import pickle
import re
import sys

SOURCES = {
    "8": {"Rhino": "Rhino", "Grasshopper": "Grasshopper", "label": "8.20 typed stubs"},
    "7": {"Rhino": "Rhino-stubs", "Grasshopper": "Grasshopper-stubs", "label": "7.7 stubs"},
}


# ---- the published stubs -------------------------------------------------------------------

class PyClass:
    def __init__(self, name, bases):
        self.name = name
        self.bases = bases
        self.functions = {}  # name -> list of (kind, params, returns, static)
        self.enum = {}


def annotation(node):
    return "" if node is None else ast.unparse(node)


def parse_module(path):
    """Classes of one .pyi module: methods with parameters, properties, enum values."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    # Members named like Python keywords ("assert = 4" in an enum, a parameter named "from")
    # are not valid Python: enum members become the comments read below, parameters get a
    # trailing underscore, and any other line Python cannot read becomes a placeholder.
    keywords = "|".join(sorted(keyword.kwlist, key=len, reverse=True))
    for i, line in enumerate(lines):
        line = re.sub(r"^(\s+)(%s)(\s*=\s*-?\d+\s*)$" % keywords, r"\1# \2\3", line)
        lines[i] = re.sub(r"([(,]\s*)(%s)(\s*:)" % keywords, r"\1\2_\3", line)
    while True:
        try:
            tree = ast.parse("\n".join(lines))
            break
        except SyntaxError as e:
            bad = lines[e.lineno - 1]
            lines[e.lineno - 1] = bad[:len(bad) - len(bad.lstrip())] + "def _unreadable_(self): ..."
    classes = {}
    for node in tree.body:
        if not isinstance(node, ast.ClassDef):
            continue
        c = PyClass(node.name, [annotation(b) for b in node.bases])
        for item in node.body:
            if isinstance(item, ast.Assign) and len(item.targets) == 1 and isinstance(item.targets[0], ast.Name):
                try:
                    c.enum[item.targets[0].id] = int(ast.literal_eval(item.value))
                except (ValueError, TypeError):
                    pass
            if not isinstance(item, ast.FunctionDef):
                continue
            decorators = [annotation(d) for d in item.decorator_list]
            args = item.args.args
            first = args[0].arg if args else None
            static = "staticmethod" in decorators or "classmethod" in decorators or first not in ("self", "cls")
            if first == "self" or ("classmethod" in decorators and first == "cls"):
                args = args[1:]
            params = [annotation(a.annotation) for a in args]
            if "property" in decorators:
                kind = "get"
            elif any(d.endswith(".setter") for d in decorators):
                kind = "set"
            else:
                kind = "method"
            c.functions.setdefault(item.name, []).append((kind, params, annotation(item.returns), static))
        # Enum members named like Python keywords are written as comments: "# None = 1".
        for line in lines[node.lineno - 1:node.end_lineno]:
            m = re.match(r"\s+#\s*(\w+)\s*=\s*(-?\d+)\s*$", line)
            if m:
                c.enum[m.group(1)] = int(m.group(2))
        classes[node.name] = c
    return classes


def cached_parse(path):
    """parse_module, kept in a pickle beside the dump's cache folder (CHECK_GH_STUBS_CACHE) so
    that repeated runs (the self-test runs the check several times) read each module once."""
    folder = os.environ.get("CHECK_GH_STUBS_CACHE")
    if not folder:
        return parse_module(path)
    stat = os.stat(path)
    name = re.sub(r"[^A-Za-z0-9]+", "_", os.path.relpath(path, "/")) + ".pickle"
    cache = os.path.join(folder, name)
    try:
        with open(cache, "rb") as f:
            stamp, classes = pickle.load(f)
        if stamp == (stat.st_size, stat.st_mtime_ns):
            return classes
    except (OSError, EOFError, pickle.PickleError, ValueError, AttributeError):
        pass
    classes = parse_module(path)
    os.makedirs(folder, exist_ok=True)
    with open(cache, "wb") as f:
        pickle.dump(((stat.st_size, stat.st_mtime_ns), classes), f)
    return classes


class Published:
    """One flavour (7 or 8) of the published stubs, parsed module by module on demand."""

    def __init__(self, flavour, site):
        self.flavour = flavour
        self.site = site
        self.label = SOURCES[flavour]["label"]
        self.modules = {}

    def module(self, namespace):
        if namespace not in self.modules:
            parts = namespace.split(".")
            root = SOURCES[self.flavour].get(parts[0])
            path = None if root is None else os.path.join(self.site, root, *parts[1:], "__init__.pyi")
            self.modules[namespace] = cached_parse(path) if path and os.path.exists(path) else {}
        return self.modules[namespace]

    def find(self, namespace, name):
        return self.module(namespace).get(name)

    def find_anywhere(self, name, near):
        """A class by short name: in the namespace `near`, its parents, then any parsed module."""
        parts = near.split(".")
        for i in range(len(parts), 0, -1):
            c = self.find(".".join(parts[:i]), name)
            if c:
                return c
        for classes in self.modules.values():
            if name in classes:
                return classes[name]
        return None

    def lineage(self, cls, namespace):
        """The class and all its published bases (the stubs list inherited members flattened,
        but not always)."""
        seen, order, queue = set(), [], [cls]
        while queue:
            c = queue.pop(0)
            if c is None or c.name in seen:
                continue
            seen.add(c.name)
            order.append(c)
            for b in c.bases:
                short = re.sub(r"\[.*", "", b).split(".")[-1]
                queue.append(self.find_anywhere(short, namespace))
        return order


# ---- C# types as each flavour spells them ---------------------------------------------------

INTEGERS = {"System.Int16", "System.Int32", "System.Int64", "System.UInt16", "System.UInt32", "System.UInt64",
            "System.Byte", "System.SByte"}


def split_generic(name):
    if "<" not in name:
        return name, []
    head, inner = name[:name.index("<")], name[name.index("<") + 1:-1]
    args, depth, start = [], 0, 0
    for i, ch in enumerate(inner):
        if ch == "<":
            depth += 1
        elif ch == ">":
            depth -= 1
        elif ch == "," and depth == 0:
            args.append(inner[start:i])
            start = i + 1
    args.append(inner[start:])
    return head, args


def spellings(cs, flavour):
    """Every way the published stubs of `flavour` write the C# type `cs`."""
    if cs.endswith("[]"):
        inner = spellings(cs[:-2], flavour)
        if flavour == "8":
            return {"Iterable[%s]" % s for s in inner}
        return {"Set(%s)" % s for s in inner} | {"Iterable[%s]" % s for s in inner}
    head, args = split_generic(cs)
    if args:
        inner = [spellings(a, flavour) for a in args]
        if head in ("System.Collections.Generic.IEnumerable",):
            return {"Iterable[%s]" % s for s in inner[0]}
        if head in ("System.Collections.Generic.List", "System.Collections.Generic.IList"):
            return {"MutableSequence[%s]" % s for s in inner[0]} if flavour == "8" else {"List", "IList"} | {"List[%s]" % s for s in inner[0]}
        return {head.split(".")[-1].split("+")[-1]}
    if "." not in cs:
        return {cs}  # a generic parameter such as T
    simple = {
        "System.Double": {"float"}, "System.Boolean": {"bool"}, "System.String": {"str"}, "System.Void": {"None"},
        "System.Single": {"float"} if flavour == "8" else {"Single"},
        "System.Object": {"object"} if flavour == "8" else {"Object"},
        "System.Collections.IEnumerable": {"Iterable[Any]"} if flavour == "8" else {"IEnumerable"},
    }
    if cs in simple:
        return simple[cs]
    if cs in INTEGERS:
        return {"int"} if flavour == "8" or cs == "System.Int32" else {cs.split(".")[-1]}
    return {cs.split(".")[-1].split("+")[-1]}


def normalise(text):
    return text.replace("typing.", "").replace("Tuple[", "tuple[").replace(" ", "")


def expected_signature(member, flavour):
    """(parameter spellings, return spellings) as the published stubs would write them."""
    params, outs = [], []
    for p in member.get("parameters", []):
        s = spellings(p["type"], flavour)
        if p["mode"] == "out":
            outs.append(s)
        else:
            params.append(s)
            if p["mode"] == "ref":
                outs.append(s)
    returns = spellings(member.get("returns", "System.Void"), flavour)
    if outs:
        first = [] if member.get("returns", "System.Void") == "System.Void" else [returns]
        combos = [[]]
        for part in first + outs:
            combos = [c + [s] for c in combos for s in part]
        returns = {"tuple[%s]" % ",".join(c) for c in combos}
    return params, returns


def matches(spelled, text):
    return normalise(text) in {normalise(s) for s in spelled}


# ---- the check ------------------------------------------------------------------------------

def signature_key(m, types):
    """The ledger's spelling of a member: type, access, modifiers, kind and C# signature."""
    t = m["type"]
    bits = [m.get("access", "public")]
    if m.get("static"):
        bits.append("static")
    if m.get("modifier"):
        bits.append(m["modifier"])
    params = ", ".join((p["mode"] + " " if p["mode"] else "") + p["type"] for p in m.get("parameters", []))
    kind = m["kind"]
    if kind == "constructor":
        body = "%s(%s)" % (t.split(".")[-1].split("+")[-1], params)
    elif kind in ("property", "indexer"):
        acc = " ".join(x for x in ("get;" if m["get"] else "", "set;" if m["set"] else "") if x)
        name = "this[%s]" % params if kind == "indexer" else m["name"]
        body = "%s %s { %s }" % (m["returns"], name, acc)
    elif kind == "enumvalue":
        body = "%s = %d" % (m["name"], m["value"])
    elif kind == "field":
        body = "%s%s %s" % ("readonly " if m["readonly"] else "", m["returns"], m["name"])
    elif kind == "delegate":
        body = "delegate %s(%s) -> %s" % (t.split(".")[-1], params, m["returns"])
    else:
        generic = "<%s>" % ",".join(m["generic_arguments"]) if m.get("generic_arguments") else ""
        body = "%s %s%s(%s)" % (m["returns"], m["name"], generic, params)
    return "%s: %s %s" % (t, " ".join(bits), body)


def find_member(pub, type_info, m):
    """Why `m` is not in the published stubs of one flavour, or None if it is."""
    ns, short = type_info["namespace"], type_info["type"].split(".")[-1]
    cls = pub.find(ns, short)
    if cls is None:
        return "type %s not in the %s" % (type_info["type"], pub.label)
    lineage = pub.lineage(cls, ns)
    kind = m["kind"]
    if kind == "enumvalue":
        if m["name"] not in cls.enum:
            return "enum member %s.%s not in the %s" % (short, m["name"], pub.label)
        if cls.enum[m["name"]] != m["value"]:
            return "enum member %s.%s is %d in the %s, %d in the stub" % (short, m["name"], cls.enum[m["name"]], pub.label, m["value"])
        return None
    if kind == "delegate":
        name, want_static = "Invoke", False
    elif kind == "constructor":
        name, want_static = "__init__", False
    elif kind == "indexer":
        name, want_static = ("__getitem__" if pub.flavour == "8" else "Item"), False
    else:
        name, want_static = m["name"], m["static"]
    candidates = []
    for c in (lineage if kind != "constructor" else [cls]):
        candidates.extend(c.functions.get(name, []))
    params, returns = expected_signature(m, pub.flavour)
    if kind == "indexer" and pub.flavour == "8" and not candidates:
        # Some typed stubs show an indexer as an Item property of a sequence.
        items = [f for c in lineage for f in c.functions.get("Item", []) if f[0] == "get"]
        element = spellings(m["returns"], "8")
        if any(matches({"%s[%s]" % (seq, e) for seq in ("Sequence", "MutableSequence") for e in element}, f[2]) for f in items):
            return None
    if not candidates:
        return "%s %s.%s not in the %s" % (kind, short, name, pub.label)
    if kind in ("property",):
        getters = [f for f in candidates if f[0] == "get"]
        setters = [f for f in candidates if f[0] == "set"]
        if m["get"] and not any(matches(returns, f[2]) and f[3] == want_static for f in getters):
            found = ", ".join("%s%s" % ("static " if f[3] else "", f[2]) for f in getters) or "no getter"
            return "property %s.%s: stub has %s%s { get; }, the %s have %s" % (short, name, "static " if want_static else "", m["returns"], pub.label, found)
        if m["set"] and not setters:
            return "property %s.%s: stub has a setter, the %s have none" % (short, name, pub.label)
        if m["set"] and not any(len(f[1]) == 1 and matches(returns, f[1][0]) for f in setters):
            return "property %s.%s: the %s setter takes another type" % (short, name, pub.label)
        return None
    if kind == "indexer" and pub.flavour == "7":
        candidates = [("method", f[1], f[2], f[3]) for f in candidates]
    for f in candidates:
        fkind, fparams, freturns, fstatic = f
        if fkind != "method" or len(fparams) != len(params):
            continue
        if not all(matches(s, p) for s, p in zip(params, fparams)):
            continue
        if kind not in ("constructor", "delegate") and fstatic != want_static:
            continue
        if kind == "constructor" or matches(returns, freturns):
            return None
    shown = "; ".join("%s(%s) -> %s" % ("static " if f[3] else "", ", ".join(f[1]), f[2]) for f in candidates if f[0] == "method")
    want = "%s(%s) -> %s" % ("static " if want_static else "", ", ".join("|".join(sorted(s)) for s in params), "|".join(sorted(returns)))
    return "%s %s.%s: no published overload matches %s; the %s have: %s" % (kind, short, name, want, pub.label, shown)


def main(argv):
    if len(argv) != 4:
        print(__doc__)
        return 2
    dump, site, ledger_path = argv[1:]
    entries = [json.loads(line) for line in open(dump, encoding="utf-8") if line.strip()]
    types = {e["type"]: e for e in entries if e["kind"] == "type"}
    members = [e for e in entries if e["kind"] != "type"]
    published = [Published("8", site), Published("7", site)]
    for p in published:
        for root in ("Rhino", "Grasshopper"):
            if not os.path.isdir(os.path.join(site, SOURCES[p.flavour][root])):
                print("check-gh-stubs: %s not installed under %s" % (SOURCES[p.flavour][root], site))
                return 2

    ledger = {}
    for number, line in enumerate(open(ledger_path, encoding="utf-8"), 1):
        line = line.rstrip("\n")
        if not line.strip() or line.startswith("#"):
            continue
        parts = [x.strip() for x in line.split(" | ")]
        if len(parts) != 3 or not parts[2].startswith("https://"):
            print("ledger line %d: expected 'signature | documented syntax | https://...'" % number)
            return 1
        ledger[parts[0]] = (number, parts[1], parts[2])

    failures, by_stubs, by_ledger, used_ledger = [], 0, 0, set()
    for t in types.values():
        # Base types: must be among the published class's bases (transitively).
        if t["nested"] or t["generic"]:
            continue
        for p in published:
            cls = p.find(t["namespace"], t["type"].split(".")[-1])
            if cls is None:
                failures.append("type %s not in the %s" % (t["type"], p.label))
                continue
            known = {c.name for c in p.lineage(cls, t["namespace"])}
            known |= {re.sub(r"\[.*", "", b).split(".")[-1] for c in p.lineage(cls, t["namespace"]) for b in c.bases}
            for b in t["bases"]:
                if b.startswith("System."):
                    continue  # IComparable and the like: the stubs list .NET's own interfaces unevenly
                short = split_generic(b)[0].split(".")[-1]
                if short not in known and short not in ("IEnumerable", "ICloneable", "IDisposable", "IEquatable"):
                    failures.append("type %s: base %s not among the %s's bases (%s)" % (t["type"], b, p.label, ", ".join(sorted(known))))

    for m in members:
        t = types[m["type"]]
        key = signature_key(m, types)
        hidden = t["nested"] or t["generic"] or m.get("access") == "protected"
        if m["kind"] == "field":
            hidden = True
        if not hidden:
            for p in published:
                why = find_member(p, t, m)
                if why:
                    failures.append(why)
            by_stubs += 1
        if hidden or m.get("modifier"):
            if key not in ledger:
                failures.append("not provable from the published stubs and missing from the ledger: " + key)
            else:
                used_ledger.add(key)
                by_ledger += 1
    for key, (number, _, _) in ledger.items():
        if key not in used_ledger:
            failures.append("ledger line %d matches no stub member: %s" % (number, key))

    for f in failures:
        print("check-gh-stubs: " + f)
    print("check-gh-stubs: %d types, %d members; %d proven by the published stubs (%s and %s), %d (protected, nested, "
          "generic or virtual/abstract/override) by the ledger; %d mismatches"
          % (len(types), len(members), by_stubs, published[0].label, published[1].label, by_ledger, len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
