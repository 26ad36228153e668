"""Every property of the filter has the same name and default in the C++
code, in the plugin's XML and in the user guide's property table.

    python3 TestPropertyDocs.py SOURCE_DIR

* Code: the properties are the vtkSet...Macro names of the header
  (Filters/vtkMeshProjectionFilter.h), plus the two array selections
  (GetPointDataArraySelection, GetCellDataArraySelection), whose default is
  "all", the strings set by `Set<Name>(const char*)` (an array's name:
  "none" when empty) and the name lists emptied by `Clear<Name>()` with a
  `std::vector<std::string> <Name>; ///< empty: all` (or `none`; or a std::set) in
  Settings.h, whose comment says what an empty list means; their defaults are the initializers of the fields of the same
  names in Filters/Projection/Settings.h, the one place they are written
  (`mp::ExtrapolationMode Extrapolation = mp::ExtrapolationMode::None;`,
  enumerators resolved from the headers under Filters/). CellDataQuantity
  and MassMatrix are the bools Extensive and Lumped there (0 or 1).
* XML (Plugin/MeshProjection.xml): the proxy's Int/Double/StringVector
  properties (not information-only), their command (Set<Name>) and
  default_values; a "Default: X" in a property's help must agree too; a
  one-element StringVectorProperty is an array's name ("None": none), a
  repeated one a list (its default is the code's: the XML has none).
* User guide (docs/user-guide.md): the table under "## Properties" whose
  header starts with `| property | default |`; a default is "all", "none",
  "on", "off", a number, or "`CONSTANT` (number)" (the header's constant of that
  value); the third column is the panel group, as in the XML's
  PropertyGroups.
Also: the header's class comment points at docs/user-guide.md.
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

ALL = "all"
NONE = "none"
LIST = "a list"  # the XML's repeated StringVectorProperty: no default of its own
# Settings.h's lists of names and what an empty one means.
LISTS = re.compile(r"^\s*std::(?:vector|set)<std::string>\s+(\w+)\s*;\s*///<\s*empty:\s*(all|none)\b", re.M)


def number(text):
    return float(text)


# Properties whose field in Settings.h has another name: a bool, true for the constant 1.
BOOL_FIELDS = {"CellDataQuantity": "Extensive", "MassMatrix": "Lumped"}


def enumerators(root):
    """Enum::Name -> value for every enum with explicit values in the headers under Filters/."""
    values = {}
    for folder, _, files in os.walk(os.path.join(root, "Filters")):
        for f in files:
            if not f.endswith(".h"):
                continue
            src = open(os.path.join(folder, f), encoding="utf-8").read()
            for enum, body in re.findall(r"\benum\s+(?:class\s+)?(\w+)[^{;]*\{([^}]*)\}", src):
                for name, value in re.findall(r"\b(\w+)\s*=\s*(-?\d+)", body):
                    values["%s::%s" % (enum, name)] = int(value)
    return values


def settings_defaults(root):
    """The initializers of Settings.h's struct Settings: field -> number (or the text if not one)."""
    src = open(os.path.join(root, "Filters", "Projection", "Settings.h"), encoding="utf-8").read()
    body = re.search(r"\bstruct\s+Settings\s*\{(.*?)\n\};", src, re.S)
    if not body:
        raise SystemExit("Settings.h: no struct Settings")
    # Settings.h's own unscoped enumerators, bare; any header's as Enum::Name.
    own = {}
    for enum_body in re.findall(r"\benum\b[^{;]*\{([^}]*)\}", src):
        for name, value in re.findall(r"\b(\w+)\s*=\s*(-?\d+)", enum_body):
            own[name] = int(value)
    scoped = enumerators(root)
    defaults = {}
    for name, value in re.findall(
            r"^\s*[\w:]+\s+(\w+)\s*=\s*([^;]+);", body.group(1), re.M):
        value = value.strip()
        qualified = "::".join(value.split("::")[-2:])
        if value in ("true", "false"):
            defaults[name] = 1.0 if value == "true" else 0.0
        elif value in own:
            defaults[name] = float(own[value])
        elif qualified in scoped:
            defaults[name] = float(scoped[qualified])
        else:
            try:
                defaults[name] = number(value.rstrip("fF"))
            except ValueError:
                defaults[name] = value  # reported below if a property's
    return defaults


def header_properties(path, root):
    src = open(path, encoding="utf-8").read()
    enums = {}
    for body in re.findall(r"\benum\b[^{;]*\{([^}]*)\}", src):
        for name, value in re.findall(r"\b([A-Z][A-Z0-9_]*)\s*=\s*(-?\d+)", body):
            enums[name] = int(value)
    names = re.findall(r"\bvtkSet(?:Clamp)?Macro\(\s*(\w+)\s*,", src)
    defaults = settings_defaults(root)
    props = {}
    for name in names:
        field = BOOL_FIELDS.get(name, name)
        if field not in defaults:
            raise SystemExit("Settings.h: %s has a vtkSet macro in the header but no field %s "
                             "with an initializer" % (name, field))
        if not isinstance(defaults[field], float):
            raise SystemExit("Settings.h: %s's initializer %r is not a number, bool or enumerator"
                             % (field, defaults[field]))
        props[name] = defaults[field]
    # Strings (a Source array's name; "" is none) and name lists.
    for name in re.findall(r"\bvoid\s+Set(\w+)\(const char\*", src):
        if name in defaults:
            props[name] = NONE if defaults[name] in ('""', "") else defaults[name]
    settings = open(os.path.join(root, "Filters", "Projection", "Settings.h"), encoding="utf-8").read()
    lists = dict(LISTS.findall(settings))
    for name in re.findall(r"^\s*std::(?:vector|set)<std::string>\s+(\w+)\s*;", settings, re.M):
        if name not in lists:
            raise SystemExit("Settings.h: the list %s does not say '///< empty: all' or "
                             "'///< empty: none'" % name)
    for name in re.findall(r"\bvoid\s+Clear(\w+)\(\)", src):
        if name in lists:
            props[name] = ALL if lists[name] == "all" else NONE
    if "GetPointDataArraySelection" in src:
        props["PointDataArrays"] = ALL
    if "GetCellDataArraySelection" in src:
        props["CellDataArrays"] = ALL
    comment = re.search(r"/\*\*.*?@class.*?\*/", src, re.S)
    return props, comment.group(0) if comment else "", enums


def xml_properties(path, problems):
    root = ET.parse(path).getroot()
    proxy = root.find(".//SourceProxy")
    props = {}
    for element in proxy:
        if element.tag not in ("IntVectorProperty", "DoubleVectorProperty", "StringVectorProperty"):
            continue
        if element.get("information_only") == "1":
            continue
        name = element.get("name")
        command = element.get("command")
        if element.tag == "StringVectorProperty":
            # One array's name (NONE when empty or the panel's "None"), else a list.
            single = element.get("number_of_elements") == "1" and element.get("repeat_command") != "1"
            value = element.get("default_values", "")
            props[name] = (NONE if value in ("", "None") else value) if single else LIST
            if single and command != "Set" + name:
                problems.append("XML: %s calls %s, not Set%s" % (name, command, name))
            if not single and (command or "").startswith("Add") and command != "Add" + name[:-1]:
                problems.append("XML: list %s calls %s, not Add%s" % (name, command, name[:-1]))
            continue
        if command != "Set" + name:
            problems.append("XML: %s calls %s, not Set%s" % (name, command, name))
        values = element.get("default_values")
        if values is None:
            problems.append("XML: %s has no default_values" % name)
            continue
        props[name] = number(values)
        doc = element.find("Documentation")
        text = " ".join((doc.text or "").split()) if doc is not None else ""
        for stated in re.findall(r"\bDefault:?\s+(-?[0-9.]+)", text):
            if number(stated.rstrip(".")) != props[name]:
                problems.append("XML: %s's help says default %s, default_values is %s"
                                % (name, stated, values))
    groups = {}
    for group in proxy.findall("PropertyGroup"):
        for member in group.findall("Property"):
            groups[member.get("name")] = group.get("label")
    return props, groups


def guide_properties(path, problems, enums):
    lines = open(path, encoding="utf-8").read().split("\n")
    start = None
    for i, line in enumerate(lines):
        if line.strip() == "## Properties":
            start = i
            break
    if start is None:
        raise SystemExit("user guide: no '## Properties' section")
    props = {}
    groups = {}
    table = False
    for line in lines[start + 1:]:
        if line.startswith("## "):
            break
        if re.match(r"^\|\s*property\s*\|\s*default\s*\|", line):
            table = True
            continue
        if table and not line.startswith("|"):
            break
        if not table or re.match(r"^\|\s*-", line):
            continue
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        m = re.fullmatch(r"`(\w+)`", cells[0])
        if not m:
            problems.append("user guide: property cell %r is not one `Name`" % cells[0])
            continue
        text = cells[1]
        if text in (ALL, NONE):
            value = text
        elif text == "on":
            value = 1.0
        elif text == "off":
            value = 0.0
        else:
            e = re.fullmatch(r"`(\w+)`\s*\((-?[0-9.]+)\)", text)
            if e and enums.get(e.group(1)) != int(float(e.group(2))):
                problems.append("user guide: %s's default %s is %s in the header"
                                % (m.group(1), text, enums.get(e.group(1), "not a constant")))
            try:
                value = number(e.group(2)) if e else number(text)
            except ValueError:
                problems.append("user guide: %s's default %r is not all/on/off/a number/`NAME` (n)"
                                % (m.group(1), text))
                continue
        if m.group(1) in props:
            problems.append("user guide: %s is listed twice" % m.group(1))
        props[m.group(1)] = value
        if len(cells) > 2:
            groups[m.group(1)] = cells[2]
    if not props:
        problems.append("user guide: no property table under '## Properties'")
    return props, groups


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    problems = []
    header, comment, enums = header_properties(
        os.path.join(root, "Filters", "vtkMeshProjectionFilter.h"), root)
    xml, xml_groups = xml_properties(os.path.join(root, "Plugin", "MeshProjection.xml"), problems)
    guide, guide_groups = guide_properties(os.path.join(root, "docs", "user-guide.md"), problems, enums)
    for name in sorted(set(xml_groups) | set(guide_groups)):
        if xml_groups.get(name) != guide_groups.get(name):
            problems.append("%s: panel group %r in the XML, %r in the user guide"
                            % (name, xml_groups.get(name), guide_groups.get(name)))
    if "docs/user-guide.md" not in comment:
        problems.append("header: the class comment does not point at docs/user-guide.md")
    sources = {"code": header, "XML": xml, "user guide": guide}
    names = set(header) | set(xml) | set(guide)
    for name in sorted(names):
        seen = {where: props[name] for where, props in sources.items() if name in props}
        if seen.get("XML") == LIST and seen.get("code") in (ALL, NONE):
            seen["XML"] = seen["code"]  # (a list's default lives in the code only)
        missing = [where for where in sources if where not in seen]
        if missing:
            problems.append("%s: missing from %s (present in %s)"
                            % (name, ", ".join(missing), ", ".join(seen)))
            continue
        if len(set(map(str, seen.values()))) != 1:
            problems.append("%s: defaults differ: %s" % (name, seen))
    print("%d properties: %s" % (len(names), ", ".join(sorted(names))))
    if problems:
        print("FAILED:\n  " + "\n  ".join(problems))
        return 1
    print("every property has one name and one default in the code (the header's setters, Settings.h), "
          "the XML and the user guide")
    return 0


if __name__ == "__main__":
    sys.exit(main())
