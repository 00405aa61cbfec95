"""Generates x3d_core/model/standard_nodes.py from the X3D Unified Object Model 4.0.

    .venv/bin/python -m x3d_core.model.uom [PATH_TO_UOM]

(default ../shared/reference/X3dUnifiedObjectModel-4.0.xml). The UOM ships with the
project's shared folder, not with x3drbp, so the table it yields is kept in the project.
"""

from __future__ import annotations

import os
import sys
from typing import Any

from lxml import etree

from x3d_core.files import atomic

from . import fields as F
from .schema import NODE_TYPES

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))  # the project's folder
UOM = os.path.normpath(os.path.join(ROOT, "..", "shared", "reference", "X3dUnifiedObjectModel-4.0.xml"))
TABLE = os.path.join(HERE, "standard_nodes.py")

# Attributes of every XML element, not fields of a node; 'field' is the <field> element
# of the nodes that declare fields (Script, the programmable shaders)
NOT_FIELDS = frozenset({"DEF", "USE", "class", "id", "style", "IS", "field"})
# Concrete in the UOM, but a statement in every encoding (the loaders read it)
STATEMENTS = frozenset({"ProtoInstance"})
# The UOM's XML Schema type of a VertexAttribute's name: an SFString in every encoding
TYPE_ALIASES = {"xs:NMTOKEN": "SFString"}

_HEAD = '''"""X3D 4.0 node types that node_defs.py leaves out, generated from the X3D Unified Object
Model 4.0 by .venv/bin/python -m x3d_core.model.uom (do not edit): node_defs.py's text form, with no
ranges or units. x3d_core.model.schema reads a type on first use.
"""

DEFINITIONS = r"""
'''


def interface_fields(el: etree._Element) -> dict[str, etree._Element]:
    """A node type's fields in the UOM, by name (XML-only attributes left out)."""
    return {f.get("name"): f for f in el.find("InterfaceDefinition").findall("field")
            if f.get("name") not in NOT_FIELDS}


def field_type(f: etree._Element) -> F.FieldType:
    name = f.get("type")
    return F.FIELD_TYPES[TYPE_ALIASES.get(name, name)]


def default(f: etree._Element, ftype: F.FieldType) -> Any:
    """A field's UOM default as a value (a node field's is always empty)."""
    text = f.get("default")
    if text is None or ftype.kind == "node":
        return F.empty(ftype)
    return F.parse_xml(ftype, text)


def parents(el: etree._Element) -> list[str]:
    return [i.get("baseType") for i in el.find("InterfaceDefinition")
            if i.tag in ("Inheritance", "AdditionalInheritance") and i.get("baseType")]


def _field_line(f: etree._Element) -> str:
    ftype = field_type(f)
    line = f"  {f.get('name')} {ftype.name} {f.get('accessType')}"
    if ftype.kind == "node" and f.get("acceptableNodeTypes"):
        line += f" <{f.get('acceptableNodeTypes')}>"
    value = default(f, ftype)
    if ftype.kind != "node" and not F.values_equal(ftype, value, F.empty(ftype)):
        line += " = " + F.format_vrml(ftype, value).removeprefix("[ ").removesuffix(" ]")
    if "#" in line or '"""' in line:
        raise ValueError(f"{line.strip()}: would read as a comment, or end the table's string")
    return line


def _abstract(el: etree._Element) -> str:
    bases = parents(el)
    return f"abstract {el.get('name')}" + (f" : {' '.join(bases)}" if bases else "")


def _concrete(el: etree._Element) -> list[str]:
    idef = el.find("InterfaceDefinition")
    comp = idef.find("componentInfo")
    head = (f"node {el.get('name')} : {' '.join(parents(el))} @{idef.find('containerField').get('default')}"
            f"  # {comp.get('name')} {comp.get('level')}")
    return [head, *(_field_line(f) for f in interface_fields(el).values())]


def generate(tree: etree._ElementTree) -> str:
    """The text of standard_nodes.py for a parsed UOM."""
    lines = [_abstract(el) for el in tree.iter("AbstractNodeType", "AbstractObjectType")
             if el.get("name") not in NODE_TYPES]
    for el in tree.iter("ConcreteNode"):
        if el.get("name") not in NODE_TYPES and el.get("name") not in STATEMENTS:
            lines += _concrete(el)
    return _HEAD + "\n".join(lines) + '\n"""\n'


if __name__ == "__main__":
    atomic.write_text(TABLE, generate(etree.parse(sys.argv[1] if len(sys.argv) > 1 else UOM)))
