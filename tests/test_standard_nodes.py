"""X3D 4.0 nodes x3drbp types from the UOM's table (x3d_core/model/standard_nodes.py): each goes
to its default containerField in every encoding, its fields are typed and checked, and the
writers write it back."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import pytest

from x3d_core.encodings.load import load
from x3d_core.encodings.model_diff import differences
from x3d_core.encodings.vrml_writer import write_vrml
from x3d_core.encodings.xml_writer import write_xml
from x3d_core.model.scene import Scene

# Capsule is no X3D 4.0 node (the UOM has none): it stays untyped, so XML names its field.
SCENE_XML = """<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Full" version="4.0">
  <Scene>
    <Transform DEF="Stage">
      <Shape>
        <Appearance>
          <PhysicalMaterial baseColor="0.2 0.4 0.6" metallic="0.5" roughness="0.25"/>
          <MultiTexture mode='"MODULATE" "ADD"'>
            <ImageTexture DEF="Brick" url='"brick.png"'>
              <TextureProperties anisotropicDegree="4" boundaryModeS="CLAMP"/>
            </ImageTexture>
            <PixelTexture image="2 1 3 0xFF0000 0x00FF00"/>
            <MovieTexture url='"clip.mp4"' loop="true" speed="2"/>
          </MultiTexture>
          <TextureTransform rotation="0.5" scale="2 2"/>
          <ComposedShader DEF="Glow" language="GLSL">
            <field name="tint" type="SFColor" accessType="inputOutput" value="1 0.5 0"/>
            <ShaderPart type="VERTEX"><![CDATA[void main() { gl_Position = vec4(0.0); }]]></ShaderPart>
            <ShaderPart type="FRAGMENT" url='"glow.frag"'/>
          </ComposedShader>
        </Appearance>
        <Text string='"x3drbp" "rigid bodies"' length="3 0" maxExtent="5">
          <FontStyle family='"SANS"' size="0.5" justify='"MIDDLE" "BEGIN"'/>
        </Text>
      </Shape>
      <Shape>
        <Appearance>
          <TwoSidedMaterial diffuseColor="1 0 0" backDiffuseColor="0 0 1" separateBackColor="true"/>
          <FillProperties hatched="false" hatchStyle="3"/>
          <LineProperties linewidthScaleFactor="2" linetype="2"/>
        </Appearance>
        <Extrusion crossSection="1 0, 0 1, -1 0, 1 0" spine="0 0 0, 0 2 0, 1 3 0" scale="1 1, 0.5 0.5, 0.25 0.25"
                   solid="false"/>
      </Shape>
      <Shape>
        <Appearance><UnlitMaterial emissiveColor="0 1 0"/></Appearance>
        <IndexedLineSet coordIndex="0 1 2 -1" colorPerVertex="false" colorIndex="0">
          <ColorRGBA color="1 0 0 0.5"/>
          <Coordinate point="0 0 0, 1 0 0, 1 1 0"/>
        </IndexedLineSet>
      </Shape>
      <Shape>
        <PointSet><CoordinateDouble point="0.1 0.2 0.3, 1e10 0 -1"/></PointSet>
      </Shape>
      <Shape>
        <Appearance><Material/><ImageTexture USE="Brick"/></Appearance>
        <IndexedFaceSet coordIndex="0 1 2 -1">
          <CoordinateDouble point="0 0 0, 1 0 0, 0 1 0"/>
          <ColorRGBA color="1 1 1 1, 0 0 0 1, 0.5 0.5 0.5 0.5"/>
          <FogCoordinate depth="0 0.5 1"/>
          <TextureCoordinateGenerator mode="COORD" parameter="1 2"/>
        </IndexedFaceSet>
      </Shape>
      <Shape><Capsule containerField="geometry"/></Shape>
    </Transform>
  </Scene>
</X3D>
"""

SCENE_VRML = """#X3D V4.0 utf8
PROFILE Full
DEF Stage Transform { children [
  Shape {
    appearance Appearance {
      material PhysicalMaterial { baseColor 0.2 0.4 0.6 metallic 0.5 roughness 0.25 }
      texture MultiTexture {
        mode [ "MODULATE" "ADD" ]
        texture [
          DEF Brick ImageTexture {
            url "brick.png"
            textureProperties TextureProperties { anisotropicDegree 4 boundaryModeS "CLAMP" }
          }
          PixelTexture { image 2 1 3 0xFF0000 0x00FF00 }
          MovieTexture { url "clip.mp4" loop TRUE speed 2 }
        ]
      }
      textureTransform TextureTransform { rotation 0.5 scale 2 2 }
      shaders DEF Glow ComposedShader {
        language "GLSL"
        inputOutput SFColor tint 1 0.5 0
        parts [
          ShaderPart { type "VERTEX" sourceCode "void main() { gl_Position = vec4(0.0); }" }
          ShaderPart { type "FRAGMENT" url "glow.frag" }
        ]
      }
    }
    geometry Text {
      string [ "x3drbp" "rigid bodies" ] length [ 3 0 ] maxExtent 5
      fontStyle FontStyle { family "SANS" size 0.5 justify [ "MIDDLE" "BEGIN" ] }
    }
  }
  Shape {
    appearance Appearance {
      material TwoSidedMaterial { diffuseColor 1 0 0 backDiffuseColor 0 0 1 separateBackColor TRUE }
      fillProperties FillProperties { hatched FALSE hatchStyle 3 }
      lineProperties LineProperties { linewidthScaleFactor 2 linetype 2 }
    }
    geometry Extrusion {
      crossSection [ 1 0, 0 1, -1 0, 1 0 ] spine [ 0 0 0, 0 2 0, 1 3 0 ] scale [ 1 1, 0.5 0.5, 0.25 0.25 ]
      solid FALSE
    }
  }
  Shape {
    appearance Appearance { material UnlitMaterial { emissiveColor 0 1 0 } }
    geometry IndexedLineSet {
      coordIndex [ 0 1 2 -1 ] colorPerVertex FALSE colorIndex [ 0 ]
      color ColorRGBA { color [ 1 0 0 0.5 ] }
      coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0 ] }
    }
  }
  Shape { geometry PointSet { coord CoordinateDouble { point [ 0.1 0.2 0.3, 1e10 0 -1 ] } } }
  Shape {
    appearance Appearance { material Material { } texture USE Brick }
    geometry IndexedFaceSet {
      coordIndex [ 0 1 2 -1 ]
      coord CoordinateDouble { point [ 0 0 0, 1 0 0, 0 1 0 ] }
      color ColorRGBA { color [ 1 1 1 1, 0 0 0 1, 0.5 0.5 0.5 0.5 ] }
      fogCoord FogCoordinate { depth [ 0 0.5 1 ] }
      texCoord TextureCoordinateGenerator { mode "COORD" parameter [ 1 2 ] }
    }
  }
  Shape { geometry Capsule { } }
] }
"""

SCENE_JSON = """{ "X3D": { "@profile": "Full", "@version": "4.0", "Scene": { "-children": [
  { "Transform": { "@DEF": "Stage", "-children": [
    { "Shape": {
        "-appearance": { "Appearance": {
            "-material": { "PhysicalMaterial": { "@baseColor": [0.2, 0.4, 0.6], "@metallic": 0.5,
                                                 "@roughness": 0.25 } },
            "-texture": { "MultiTexture": { "@mode": ["MODULATE", "ADD"], "-texture": [
                { "ImageTexture": { "@DEF": "Brick", "@url": ["brick.png"],
                    "-textureProperties": { "TextureProperties": { "@anisotropicDegree": 4,
                                                                   "@boundaryModeS": "CLAMP" } } } },
                { "PixelTexture": { "@image": [2, 1, 3, 16711680, 65280] } },
                { "MovieTexture": { "@url": ["clip.mp4"], "@loop": true, "@speed": 2 } } ] } },
            "-textureTransform": { "TextureTransform": { "@rotation": 0.5, "@scale": [2, 2] } },
            "-shaders": [ { "ComposedShader": { "@DEF": "Glow", "@language": "GLSL",
                "field": [ { "@name": "tint", "@type": "SFColor", "@accessType": "inputOutput",
                             "@value": [1, 0.5, 0] } ],
                "-parts": [
                  { "ShaderPart": { "@type": "VERTEX",
                                    "#sourceCode": ["void main() { gl_Position = vec4(0.0); }"] } },
                  { "ShaderPart": { "@type": "FRAGMENT", "@url": ["glow.frag"] } } ] } } ] } },
        "-geometry": { "Text": { "@string": ["x3drbp", "rigid bodies"], "@length": [3, 0], "@maxExtent": 5,
            "-fontStyle": { "FontStyle": { "@family": ["SANS"], "@size": 0.5,
                                           "@justify": ["MIDDLE", "BEGIN"] } } } } } },
    { "Shape": {
        "-appearance": { "Appearance": {
            "-material": { "TwoSidedMaterial": { "@diffuseColor": [1, 0, 0], "@backDiffuseColor": [0, 0, 1],
                                                 "@separateBackColor": true } },
            "-fillProperties": { "FillProperties": { "@hatched": false, "@hatchStyle": 3 } },
            "-lineProperties": { "LineProperties": { "@linewidthScaleFactor": 2, "@linetype": 2 } } } },
        "-geometry": { "Extrusion": { "@crossSection": [1, 0, 0, 1, -1, 0, 1, 0],
            "@spine": [0, 0, 0, 0, 2, 0, 1, 3, 0], "@scale": [1, 1, 0.5, 0.5, 0.25, 0.25],
            "@solid": false } } } },
    { "Shape": {
        "-appearance": { "Appearance": { "-material": { "UnlitMaterial": { "@emissiveColor": [0, 1, 0] } } } },
        "-geometry": { "IndexedLineSet": { "@coordIndex": [0, 1, 2, -1], "@colorPerVertex": false,
            "@colorIndex": [0],
            "-color": { "ColorRGBA": { "@color": [1, 0, 0, 0.5] } },
            "-coord": { "Coordinate": { "@point": [0, 0, 0, 1, 0, 0, 1, 1, 0] } } } } } },
    { "Shape": { "-geometry": { "PointSet": {
        "-coord": { "CoordinateDouble": { "@point": [0.1, 0.2, 0.3, 1e10, 0, -1] } } } } } },
    { "Shape": {
        "-appearance": { "Appearance": { "-material": { "Material": { } },
                                         "-texture": { "ImageTexture": { "@USE": "Brick" } } } },
        "-geometry": { "IndexedFaceSet": { "@coordIndex": [0, 1, 2, -1],
            "-coord": { "CoordinateDouble": { "@point": [0, 0, 0, 1, 0, 0, 0, 1, 0] } },
            "-color": { "ColorRGBA": { "@color": [1, 1, 1, 1, 0, 0, 0, 1, 0.5, 0.5, 0.5, 0.5] } },
            "-fogCoord": { "FogCoordinate": { "@depth": [0, 0.5, 1] } },
            "-texCoord": { "TextureCoordinateGenerator": { "@mode": "COORD", "@parameter": [1, 2] } } } } } },
    { "Shape": { "-geometry": { "Capsule": { } } } }
  ] } } ] } } }
"""

ENCODINGS = {"xml": ("scene.x3d", SCENE_XML), "vrml": ("scene.x3dv", SCENE_VRML), "json": ("scene.x3dj", SCENE_JSON)}


def _load(tmp_path: Path, name: str, text: str) -> Scene:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return load(str(p))


def _problems(s: Scene) -> list[str]:
    """Diagnostics about a node or field (a scene without bodies also draws one about the whole scene)."""
    return [str(d) for d in s.diagnostics if d.subject]


@pytest.fixture
def reference(tmp_path: Path) -> Scene:
    s = _load(tmp_path, *ENCODINGS["xml"])
    assert _problems(s) == []
    return s


def test_standard_nodes_go_to_their_default_fields_typed(reference: Scene) -> None:
    text, extrusion, lines, points, faces, capsule = reference.roots[0]["children"]
    look = text["appearance"]
    assert look["material"].type_name == "PhysicalMaterial" and look["material"]["metallic"] == 0.5
    multi = look["texture"]
    assert [t.type_name for t in multi["texture"]] == ["ImageTexture", "PixelTexture", "MovieTexture"]
    brick, pixels, movie = multi["texture"]
    assert brick["textureProperties"]["boundaryModeS"] == "CLAMP" and brick["repeatS"] is True  # a UOM default
    assert pixels["image"].tolist() == [2, 1, 3, 0xFF0000, 0x00FF00] and movie["loop"] is True
    assert look["textureTransform"]["scale"].tolist() == [2, 2]
    (shader,) = look["shaders"]
    assert [d.name for d in shader.interface] == ["tint"] and shader.interface[0].value.tolist() == [1, 0.5, 0]
    assert [(p["type"], p["sourceCode"]) for p in shader["parts"]] == \
        [("VERTEX", "void main() { gl_Position = vec4(0.0); }"), ("FRAGMENT", "")]
    assert text["geometry"]["string"] == ["x3drbp", "rigid bodies"]
    assert text["geometry"]["fontStyle"]["justify"] == ["MIDDLE", "BEGIN"]
    look = extrusion["appearance"]
    assert (look["material"].type_name, look["fillProperties"]["hatchStyle"], look["lineProperties"]["linetype"]) == \
        ("TwoSidedMaterial", 3, 2)
    assert extrusion["geometry"]["spine"].shape == (3, 3)
    assert lines["appearance"]["material"].type_name == "UnlitMaterial"
    assert lines["geometry"]["color"]["color"].tolist() == [[1, 0, 0, 0.5]]
    assert points["geometry"]["coord"]["point"][1].tolist() == [1e10, 0, -1]
    assert faces["appearance"]["texture"] is brick
    assert [faces["geometry"][f].type_name for f in ("coord", "color", "fogCoord", "texCoord")] == \
        ["CoordinateDouble", "ColorRGBA", "FogCoordinate", "TextureCoordinateGenerator"]
    assert capsule["geometry"].type_name == "Capsule"
    untyped = [n.type_name for n in reference.nodes() if n.spec is None]
    assert untyped == ["Capsule"]


@pytest.mark.parametrize("encoding", ["vrml", "json"])
def test_every_encoding_gives_the_same_model(tmp_path: Path, reference: Scene, encoding: str) -> None:
    s = _load(tmp_path, *ENCODINGS[encoding])
    assert _problems(s) == []
    assert differences(reference, s) == []


@pytest.mark.parametrize("write,name", [(write_xml, "back.x3d"), (write_vrml, "back.x3dv")])
def test_writers_write_standard_nodes_back(tmp_path: Path, reference: Scene, write: Callable[[Scene], bytes],
                                           name: str) -> None:
    p = tmp_path / name
    p.write_bytes(write(reference))
    back = load(str(p))
    assert _problems(back) == []
    assert differences(reference, back) == []


def test_differences_see_a_changed_standard_field(tmp_path: Path, reference: Scene) -> None:
    changed = _load(tmp_path, "changed.x3d", SCENE_XML.replace('hatchStyle="3"', 'hatchStyle="4"'))
    assert any("FillProperties.hatchStyle" in d for d in differences(reference, changed))


@pytest.mark.parametrize("name,text,line,subject,fragment", [
    ("bad.x3d", '<?xml version="1.0"?>\n<X3D version="4.0"><Scene>\n<Shape>\n'
                '  <Text string=\'"a"\' maxExtent="wide"/>\n</Shape></Scene></X3D>\n',
     4, "Text.maxExtent", "'wide' is not a number"),
    ("bad.x3d", '<?xml version="1.0"?>\n<X3D version="4.0"><Scene>\n'
                '<Shape><Appearance><ImageTexture DEF="T"\n  repeatX="true"/></Appearance></Shape></Scene></X3D>\n',
     4, "ImageTexture T.repeatX", "has no field 'repeatX'"),
    ("bad.x3dv", "#X3D V4.0 utf8\nPROFILE Full\nShape { geometry PointSet {\n"
                 "  coord CoordinateDouble { point [ 1 2 ] } } }\n",
     4, "CoordinateDouble.point", "not a whole number of 3-tuples"),
    ("bad.x3dj", '{ "X3D": { "@version": "4.0", "Scene": { "-children": [\n'
                 '  { "Shape": { "-appearance": { "Appearance": {\n'
                 '    "-fillProperties": { "FillProperties": { "@hatched": "no" } } } } } } ] } } }\n',
     3, "FillProperties.hatched", "expected JSON true or false"),
])
def test_a_wrong_value_is_one_line_naming_file_line_and_field(tmp_path: Path, name: str, text: str, line: int,
                                                               subject: str, fragment: str) -> None:
    s = _load(tmp_path, name, text)
    (e,) = s.errors
    assert (e.subject, e.loc.line) == (subject, line) and fragment in e.message
    message = str(e)
    assert message.startswith(f"{tmp_path / name}:{line}:") and subject in message and "\n" not in message


def test_vrml_writes_an_sfimage_as_one_unbracketed_value(reference: Scene) -> None:
    assert "image 2 1 3 16711680 65280\n" in write_vrml(reference).decode()
