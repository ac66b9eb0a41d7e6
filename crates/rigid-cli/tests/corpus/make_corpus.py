#!/usr/bin/env python3
"""Writes the malformed-input corpus of crates/rigid-cli/tests/it/corpus.rs (run from anywhere:
`python3 make_corpus.py [OUT_DIR]`; the files are committed, this script says how each was
made, and the test checks that it still writes exactly them).

Every case is a file NAME.EXT in a folder by kind (urdf, spec, mesh, cases, samples, cli) and a sidecar
NAME.expect:

    args: eval {dir}/../../fixtures/pendulum.urdf --cases {file}
    status: error
    contains: case 0 | "q" | expected nq = 1

`args` is the `rigid` command line ({file}: the case file, {dir}: its folder, {out}: an output
path that must not exist afterwards); `status` is `error` (exit code 2, exactly one line on
stderr starting with `error:`, containing every `contains` string), `warning` (exit 0, a
`warning:` line containing them) or `ok` (exit 0). No case may print `panicked`.
"""

import os
import struct
import sys

# the corpus folder (or another folder given as the argument, to check the committed files)
HERE = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))


def write(kind, name, ext, content, args, status, *contains):
    d = os.path.join(HERE, kind)
    os.makedirs(d, exist_ok=True)
    path = os.path.join(d, f"{name}.{ext}")
    mode = "wb" if isinstance(content, bytes) else "w"
    with open(path, mode) as f:
        f.write(content)
    with open(os.path.join(d, f"{name}.expect"), "w") as f:
        f.write(f"args: {args}\nstatus: {status}\ncontains: {' | '.join(contains)}\n")


# ---------------------------------------------------------------------------------------- URDF
LINK = """  <link name="{name}">
    <inertial>
      <origin xyz="0 0 -0.5" rpy="0 0 0"/>
      <mass value="{mass}"/>
      <inertia ixx="{ixx}" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>
    </inertial>
  </link>
"""


def robot(links="", joints="", name='name="r"', extra=""):
    return f'<?xml version="1.0"?>\n<robot {name}>\n  <link name="base"/>\n{links}{joints}{extra}</robot>\n'


def link(name="arm", mass="2", ixx="0.01"):
    return LINK.format(name=name, mass=mass, ixx=ixx)


def joint(name="hinge", kind="revolute", parent="base", child="arm", axis='<axis xyz="0 1 0"/>',
          origin='<origin xyz="0 0 1" rpy="0 0 0"/>',
          limit='<limit lower="-1" upper="1" effort="10" velocity="2"/>', extra=""):
    return (f'  <joint name="{name}" type="{kind}">\n    {origin}\n    <parent link="{parent}"/>\n'
            f'    <child link="{child}"/>\n    {axis}\n    {limit}\n    {extra}\n  </joint>\n')


def urdf(name, text, status, *contains, args="model {file}"):
    write("urdf", name, "urdf", text, args, status, *contains)


GOOD = robot(link(), joint())
urdf("valid_reference", GOOD, "ok")
urdf("xml_unclosed", GOOD.replace("</robot>", ""), "error", "malformed XML", "line")
urdf("xml_bad_attribute", GOOD.replace('name="arm"', "name=arm", 1), "error", "malformed XML", "line 4")
urdf("xml_two_roots", GOOD + "<robot name='x'/>", "error", "malformed XML")
urdf("xml_duplicate_attribute", GOOD.replace('<link name="base"/>', '<link name="base" name="b"/>'),
     "error", "malformed XML")
urdf("xml_empty", "", "error", "malformed XML")
urdf("xml_not_xml", "this is not a robot\n", "error", "malformed XML")
urdf("xml_entity_loop", '<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY a "&b;"><!ENTITY b "&a;">]>\n'
     '<robot name="&a;"><link name="x"/></robot>\n', "error", "malformed XML")
LAUGHS = "".join(f'<!ENTITY l{i} "{("&l" + str(i - 1) + ";") * 10 if i else "lol"}">\n'
                 for i in range(10))
urdf("xml_billion_laughs", f'<?xml version="1.0"?>\n<!DOCTYPE r [\n{LAUGHS}]>\n'
     '<robot name="&l9;"><link name="x"/></robot>\n', "error", "malformed XML")
urdf("not_a_robot", '<?xml version="1.0"?>\n<model name="m"/>\n', "error", "expected <robot>")
urdf("no_links", '<robot name="r">\n</robot>\n', "error", "no <link>")
urdf("robot_without_name", GOOD.replace('<robot name="r">', "<robot>"), "warning", "robot",
     "no \"name\" attribute")
urdf("link_without_name", GOOD.replace('<link name="base"/>', "<link/>"), "error", "link",
     "no \"name\" attribute", "line 3")
urdf("duplicate_link", robot(link() + link(), joint()), "error", 'link "arm"', "duplicate",
     "line 4")
urdf("duplicate_joint", robot(link() + link("arm2"), joint() + joint(child="arm2")), "error",
     'joint "hinge"', "duplicate joint name")
urdf("joint_without_name", GOOD.replace('joint name="hinge" ', "joint "), "error", "joint",
     "no \"name\" attribute")
urdf("joint_without_type", GOOD.replace(' type="revolute"', ""), "error", 'joint "hinge"',
     "no \"type\" attribute")
urdf("joint_unknown_type", GOOD.replace('type="revolute"', 'type="ball"'), "error",
     'joint "hinge"', "unknown joint type \"ball\"")
urdf("joint_without_parent", GOOD.replace('<parent link="base"/>', ""), "error", 'joint "hinge"',
     "no <parent>")
urdf("joint_without_child", GOOD.replace('<child link="arm"/>', ""), "error", 'joint "hinge"',
     "no <child>")
urdf("joint_parent_missing", GOOD.replace('<parent link="base"/>', '<parent link="ghost"/>'),
     "error", 'joint "hinge"', 'parent link "ghost" is not defined')
urdf("joint_child_missing", GOOD.replace('<child link="arm"/>', '<child link="ghost"/>'),
     "error", 'joint "hinge"', 'child link "ghost" is not defined')
urdf("cycle_self", GOOD.replace('<parent link="base"/>', '<parent link="arm"/>'), "error",
     'joint "hinge"', "cycle")
urdf("cycle_two_links", robot(link() + link("arm2"), joint() + joint("back", child="arm2", parent="arm")
                              + joint("loop", parent="arm2", child="arm")), "error", "two parents")
urdf("cycle_detached", robot(link() + link("arm2") + link("arm3"),
                             joint() + joint("j2", parent="arm2", child="arm3")
                             + joint("j3", parent="arm3", child="arm2")), "error", "cycle")
urdf("two_roots", robot(link() + link("stray"), joint()), "error", "no unique root", '"stray"')
urdf("two_parents", robot(link(), joint() + joint("again", parent="base", child="arm")), "error",
     'joint "again"', "two parents")
urdf("axis_zero", GOOD.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>'), "error",
     'joint "hinge"', "zero joint axis")
urdf("axis_nan", GOOD.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 nan 0"/>'), "error",
     'joint "hinge"', "non-finite")
urdf("axis_two_numbers", GOOD.replace('<axis xyz="0 1 0"/>', '<axis xyz="0 1"/>'), "error",
     'joint "hinge"', "expected 3 numbers")
urdf("axis_words", GOOD.replace('<axis xyz="0 1 0"/>', '<axis xyz="up up up"/>'), "error",
     'joint "hinge"', "not a list of 3 numbers")
urdf("origin_infinite", GOOD.replace('xyz="0 0 1"', 'xyz="0 0 inf"'), "error", 'joint "hinge"',
     "non-finite")
urdf("origin_overflow", GOOD.replace('xyz="0 0 1"', 'xyz="0 0 1e400"'), "error", 'joint "hinge"',
     "non-finite")
urdf("origin_rpy_nan", GOOD.replace('rpy="0 0 0"/>\n    <parent', 'rpy="NaN 0 0"/>\n    <parent'),
     "error", 'joint "hinge"', "non-finite")
urdf("origin_four_numbers", GOOD.replace('xyz="0 0 1"', 'xyz="0 0 1 1"'), "error",
     'joint "hinge"', "expected 3 numbers, got 4")
urdf("origin_commas", GOOD.replace('xyz="0 0 1"', 'xyz="0,0,1"'), "error", 'joint "hinge"',
     "not a list")
urdf("limit_lower_above_upper", GOOD.replace('lower="-1" upper="1"', 'lower="1" upper="-1"'),
     "warning", 'joint "hinge"', "above upper", "no position limit")
urdf("xml_declaration_after_blank_line", "\n" + GOOD, "warning", "line 2",
     "XML declaration does not stand at the start")
urdf("limit_nan", GOOD.replace('lower="-1"', 'lower="nan"'), "error", 'joint "hinge"',
     "non-finite")
urdf("limit_negative_velocity", GOOD.replace('velocity="2"', 'velocity="-2"'), "error",
     'joint "hinge"', "limits")
urdf("limit_hex", GOOD.replace('effort="10"', 'effort="0x10"'), "error", 'joint "hinge"',
     "not a number")
urdf("mass_negative", robot(link(mass="-2"), joint()), "error", 'link "arm"', "mass", "line 5")
urdf("mass_zero_with_inertia", robot(link(mass="0"), joint()), "warning", 'link "arm"', "mass")
urdf("mass_nan", robot(link(mass="nan"), joint()), "error", 'link "arm"', "non-finite")
urdf("mass_word", robot(link(mass="heavy"), joint()), "error", 'link "arm"', "not a number")
urdf("mass_huge", robot(link(mass="1e300"), joint()), "warning", 'link "arm"',
     "implausibly large")
urdf("mass_missing", robot(link().replace('      <mass value="2"/>\n', ""), joint()),
     "warning", 'link "arm"', "no <mass>")
urdf("inertia_missing", robot(link().replace(
    '      <inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/>\n', ""), joint()),
     "warning", 'link "arm"', "no <inertia>")
urdf("inertia_attribute_missing", robot(link().replace(' iyz="0"', ""), joint()), "error",
     'link "arm"', "no \"iyz\" attribute")
urdf("inertia_nan", robot(link(ixx="nan"), joint()), "error", 'link "arm"', "non-finite")
urdf("inertia_infinite", robot(link(ixx="-inf"), joint()), "error", 'link "arm"', "non-finite")
urdf("inertia_not_psd_default", robot(link(ixx="-0.01"), joint()), "warning", 'link "arm"',
     "positive semi-definite", "as written")
urdf("inertia_not_psd_strict", robot(link(ixx="-0.01"), joint()), "error", 'link "arm"',
     "line 5", "positive semi-definite", args="model {file} --inertia strict")
urdf("inertia_triangle", robot(link(ixx="0.05"), joint()), "warning", 'link "arm"', "triangle")
urdf("mimic_self", GOOD.replace('<limit lower', '<mimic joint="hinge"/><limit lower'), "error",
     'joint "hinge"', "mimics itself")
urdf("mimic_unknown", GOOD.replace('<limit lower', '<mimic joint="ghost"/><limit lower'),
     "warning", 'joint "hinge"', '"ghost"', "not defined")
urdf("mimic_loop", robot(link() + link("arm2"),
                         joint(extra='<mimic joint="j2"/>')
                         + joint("j2", parent="arm", child="arm2", extra='<mimic joint="hinge"/>')),
     "error", "mimic", "loop")
urdf("mimic_no_joint_attribute", GOOD.replace('<limit lower', '<mimic/><limit lower'), "error",
     'joint "hinge"', "no \"joint\" attribute")
urdf("planar_bad_axis", GOOD.replace('type="revolute"', 'type="planar"'), "error",
     'joint "hinge"', "planar", "0 0 1")
urdf("floating_root_name_taken", GOOD.replace('joint name="hinge"', 'joint name="root_joint"'),
     "error", "root_joint", args="model {file} --floating")
urdf("unknown_element", GOOD.replace('<link name="base"/>', '<link name="base"><sparkle/></link>'),
     "warning", "<sparkle>", "line 3")
urdf("undeclared_namespace", GOOD.replace("</robot>", "<drake:joint name='d'/>\n</robot>"),
     "warning", "drake")
urdf("geometry_negative_radius", robot(link().replace(
    "  </link>", '    <visual><geometry><cylinder radius="-1" length="1"/></geometry></visual>\n  </link>'),
    joint()), "warning", 'link "arm"', "radius")
urdf("geometry_unknown_shape", robot(link().replace(
    "  </link>", '    <collision><geometry><torus r="1"/></geometry></collision>\n  </link>'),
    joint()), "warning", 'link "arm"', "unknown geometry <torus>")
urdf("geometry_mesh_without_filename", robot(link().replace(
    "  </link>", '    <visual><geometry><mesh/></geometry></visual>\n  </link>'), joint()),
     "warning", 'link "arm"', "filename")
urdf("utf8_bom", "\ufeff" + GOOD, "ok")
urdf("utf8_names", GOOD.replace('"arm"', '"bras_épaule_肩"').replace('"hinge"', '"articulación"'),
     "ok")
write("urdf", "invalid_utf8", "urdf", GOOD.encode().replace(b'"arm"', b'"a\xff\xfem"'),
      "model {file}", "error", "invalid_utf8.urdf", "UTF-8")
urdf("control_characters", GOOD.replace('"arm"', '"a\x01rm"'), "error", "malformed XML")
urdf("only_fixed_joints", robot(link(), joint(kind="fixed", axis="", limit="")), "ok")
urdf("continuous_with_limit", GOOD.replace('type="revolute"', 'type="continuous"'), "ok")
urdf("eval_wrong_state", GOOD, "error", "case 0", '"q"', "expected nq = 1",
     args="eval {file} --cases {dir}/../cases/q_too_long.json")

# ------------------------------------------------------------------------------------ body specs
SHAPES = {
    "box": ('size = [0.2, 0.1, 0.1]', "size"),
    "cylinder": ("radius = 0.1\nlength = 0.2", "radius"),
    "sphere": ("radius = 0.1", "radius"),
    "ellipsoid": ("semi_axes = [0.1, 0.2, 0.3]", "semi_axes"),
    "capsule": ("radius = 0.1\nlength = 0.2", "length"),
    "cone": ("radius = 0.1\nheight = 0.3", "height"),
    "rod": ("length = 0.5", "length"),
}


def spec(name, text, status, *contains, args="mass {file}"):
    write("spec", name, "toml", text, args, status, *contains)


spec("valid_reference", '[[part]]\nshape = "box"\nsize = [0.2, 0.1, 0.1]\nmass = 2\n', "ok")
for shape, (dims, key) in SHAPES.items():
    mass = "mass = 2" if shape == "rod" else "density = 1000"
    base = f'[[part]]\nname = "p"\nshape = "{shape}"\n{dims}\n{mass}\n'
    line = [l.split(" = ")[0] for l in base.splitlines()]
    vec = "[" in dims.split("\n")[[l.split(" = ")[0] for l in dims.splitlines()].index(key)]
    for variant, value, expect in [
        ("missing", None, "missing"),
        ("negative", "[-0.1, 0.1, 0.1]" if vec else "-0.1", "positive"),
        ("zero", "[0.1, 0.0, 0.1]" if vec else "0.0", "positive"),
        ("nan", "[0.1, nan, 0.1]" if vec else "nan", "finite"),
        ("string", '"big"', "expected"),
    ]:
        lines = [l for l in base.splitlines() if not l.startswith(key + " =")]
        if value is not None:
            lines.insert(3, f"{key} = {value}")
        spec(f"{shape}_{key}_{variant}", "\n".join(lines) + "\n", "error", "part 1", '"p"',
             key, expect)
spec("point_with_density", '[[part]]\nshape = "point"\ndensity = 1000\n', "error", "density",
     "no volume")
spec("point_without_mass", '[[part]]\nshape = "point"\n', "error", '`mass`', "missing")
spec("mass_and_density", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\ndensity = 10\n',
     "error", "density", "not both")
spec("neither_mass_nor_density", '[[part]]\nshape = "sphere"\nradius = 0.1\n', "error", '`mass`',
     "missing")
spec("negative_mass", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = -1\n', "error", '`mass`',
     "positive")
spec("zero_density", '[[part]]\nshape = "sphere"\nradius = 0.1\ndensity = 0\n', "error",
     '`density`', "positive")
spec("infinite_mass", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = inf\n', "error", '`mass`',
     "finite")
spec("unknown_key", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\ncolour = "red"\n',
     "error", '`colour`', "unknown key")
spec("unknown_shape", '[[part]]\nshape = "torus"\nmass = 1\n', "error", '`shape`', "torus")
spec("shape_missing", "[[part]]\nmass = 1\n", "error", '`shape`', "missing")
spec("shape_not_string", "[[part]]\nshape = 3\nmass = 1\n", "error", '`shape`', "expected a string")
spec("dimension_of_another_shape", '[[part]]\nshape = "sphere"\nradius = 0.1\nsize = [1, 1, 1]\nmass = 1\n',
     "error", '`size`', "not used by shape")
spec("no_parts", "# nothing\n", "error", "no [[part]]")
spec("empty_file", "", "error", "no [[part]]")
spec("syntax_error", '[[part]\nshape = "box"\n', "error", "line 1")
spec("syntax_unterminated_string", '[[part]]\nshape = "box\n', "error", "line 2")
spec("part_not_table", "part = 3\n", "error", "part")
spec("quaternion_not_unit", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\nquaternion = [0, 0, 0, 2]\n',
     "error", '`quaternion`', "unit")
spec("quaternion_zero", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\nquaternion = [0, 0, 0, 0]\n',
     "error", '`quaternion`')
spec("quaternion_three_numbers", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\nquaternion = [0, 0, 1]\n',
     "error", '`quaternion`', "expected 4 numbers")
spec("rpy_nan", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\nrpy = [0, nan, 0]\n',
     "error", "rpy[1]", "finite")
spec("rpy_and_quaternion", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\nrpy = [0, 0, 0]\nquaternion = [0, 0, 0, 1]\n',
     "error", '`quaternion`', "not both")
spec("position_two_numbers", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\nposition = [0, 1]\n',
     "error", '`position`', "expected 3 numbers")
spec("position_string", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\nposition = "origin"\n',
     "error", '`position`', "array")
spec("inertia_five_numbers", '[[part]]\nshape = "inertia"\ninertia = [1, 1, 1, 0, 0]\nmass = 1\n',
     "error", '`inertia`', "expected 6 numbers")
spec("inertia_not_physical", '[[part]]\nshape = "inertia"\ninertia = [-1, 1, 1, 0, 0, 0]\nmass = 1\n',
     "warning", "positive semi-definite")
spec("second_part_bad", '[[part]]\nshape = "sphere"\nradius = 0.1\nmass = 1\n\n[[part]]\nname = "lid"\nshape = "box"\nsize = [1, 1]\nmass = 1\n',
     "error", "part 2", '"lid"', "line 9", "size")
spec("mesh_file_missing", '[[part]]\nshape = "mesh"\nfile = "no_such.stl"\ndensity = 1000\n',
     "error", '`file`', "no_such.stl")
spec("mesh_file_not_string", '[[part]]\nshape = "mesh"\nfile = 3\ndensity = 1000\n', "error",
     '`file`', "expected a string")
spec("mesh_unknown_extension", '[[part]]\nshape = "mesh"\nfile = "part.ply"\ndensity = 1000\n',
     "error", '`file`', "part.ply")
spec("mass_of_point_huge", '[[part]]\nshape = "point"\nmass = 1e300\n', "ok")
spec("output_not_written", '[[part]]\nshape = "box"\nsize = [1, -1, 1]\nmass = 1\n', "error",
     "size[1]", args="simulate {file} --csv {out}")

# ---------------------------------------------------------------------------------------- meshes
CUBE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_F = [(0, 3, 2), (0, 2, 1), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4), (1, 2, 6), (1, 6, 5),
          (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def ascii_stl(faces, verts=CUBE_V):
    out = ["solid cube"]
    for f in faces:
        out.append("  facet normal 0 0 0\n    outer loop")
        for i in f:
            out.append("      vertex {} {} {}".format(*verts[i]))
        out.append("    endloop\n  endfacet")
    out.append("endsolid cube\n")
    return "\n".join(out)


def binary_stl(faces, verts=CUBE_V, count=None):
    data = b"binary stl".ljust(80, b" ") + struct.pack("<I", len(faces) if count is None else count)
    for f in faces:
        data += struct.pack("<3f", 0, 0, 0)
        for i in f:
            data += struct.pack("<3f", *verts[i])
        data += b"\0\0"
    return data


def obj(faces, verts=CUBE_V, offset=1):
    return "".join("v {} {} {}\n".format(*v) for v in verts) + "".join(
        "f {} {} {}\n".format(*(i + offset for i in f)) for f in faces)


def mesh(name, ext, content, status, *contains):
    d = os.path.join(HERE, "mesh")
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, f"{name}.toml"), "w") as f:
        f.write(f'[[part]]\nname = "{name}"\nshape = "mesh"\nfile = "{name}.{ext}"\ndensity = 1000\n')
    write("mesh", name, ext, content, "mass {dir}/" + name + ".toml", status, *contains)


mesh("valid_cube_ascii", "stl", ascii_stl(CUBE_F), "ok")
mesh("valid_cube_binary", "stl", binary_stl(CUBE_F), "ok")
mesh("valid_cube_obj", "obj", obj(CUBE_F), "ok")
mesh("open_ascii", "stl", ascii_stl(CUBE_F[:-1]), "error", '`file`', "open_ascii.stl", "open")
mesh("open_obj", "obj", obj(CUBE_F[1:]), "error", '`file`', "open")
mesh("inverted", "stl", ascii_stl([(a, c, b) for a, b, c in CUBE_F]), "error", '`file`',
     "inward")
mesh("inconsistent_winding", "obj", obj([CUBE_F[0][::-1]] + CUBE_F[1:]), "error", '`file`')
mesh("non_manifold", "obj", obj(CUBE_F + [(0, 2, 1)]), "error", '`file`')
mesh("degenerate_triangle", "obj", obj(CUBE_F + [(0, 0, 1)]), "error", '`file`', "degenerate")
mesh("zero_volume", "obj", obj([(0, 1, 2), (0, 2, 1)]), "error", '`file`')
mesh("binary_count_too_large", "stl", binary_stl(CUBE_F, count=1000), "error", '`file`')
mesh("binary_count_too_small", "stl", binary_stl(CUBE_F, count=3), "error", '`file`')
mesh("binary_truncated", "stl", binary_stl(CUBE_F)[:300], "error", '`file`')
mesh("binary_nan_vertex", "stl", binary_stl(CUBE_F, verts=[(float("nan"), 0, 0)] + CUBE_V[1:]),
     "error", '`file`')
mesh("ascii_garbage", "stl", "solid x\n  facet normal a b c\n  what is this\nendsolid\n", "error",
     '`file`')
mesh("empty_stl", "stl", "", "error", '`file`')
mesh("empty_obj", "obj", "", "error", '`file`')
mesh("obj_vertices_only", "obj", obj([]), "error", '`file`', "no triangles")
mesh("obj_index_out_of_range", "obj", obj(CUBE_F[:-1] + [(3, 4, 70)]), "error", '`file`')
mesh("obj_index_zero", "obj", obj(CUBE_F, offset=0), "error", '`file`')
mesh("obj_words", "obj", "v one two three\nf 1 2 3\n", "error", '`file`')
mesh("dae_not_collada", "dae", "<model/>", "error", '`file`', "COLLADA")
mesh("dae_broken_xml", "dae", "<COLLADA><library_geometries>", "error", '`file`')
mesh("dae_index_out_of_range", "dae",
     '<COLLADA><library_geometries><geometry id="g"><mesh><source id="p"><float_array id="a" count="9">'
     '0 0 0 1 0 0 0 1 0</float_array></source><vertices id="v"><input semantic="POSITION" source="#p"/>'
     '</vertices><triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 9</p>'
     '</triangles></mesh></geometry></library_geometries></COLLADA>', "error", '`file`', "out of range")

# ------------------------------------------------------------------------------------ case files
EVAL = "eval {dir}/../../fixtures/pendulum.urdf --cases {file}"
FLOAT = "eval {dir}/../../fixtures/pendulum.urdf --floating --cases {file}"


def cases(name, text, status, *contains, args=EVAL):
    write("cases", name, "json", text, args, status, *contains)


cases("valid_reference", '{"cases": [{"q": [0.1], "v": [0.2]}]}', "ok")
cases("q_too_long", '{"cases": [{"q": [0.1, 0.2]}]}', "error", "case 0", '"q"', "expected nq = 1")
cases("q_missing", '{"cases": [{"v": [0.1]}]}', "error", "case 0", '"q"', "missing")
cases("v_too_short", '{"cases": [{"q": [0.1]}, {"q": [0.1], "v": []}]}', "error", "case 1",
      '"v"', "expected nv = 1")
cases("tau_string", '{"cases": [{"q": [0.1], "tau": ["1"]}]}', "error", "case 0", '"tau"',
      "not a number")
cases("q_null", '{"cases": [{"q": [null]}]}', "error", "case 0", '"q"', "not a number")
cases("q_nested", '{"cases": [{"q": [[0.1]]}]}', "error", "case 0", '"q"', "not a number")
cases("q_not_array", '{"cases": [{"q": 0.1}]}', "error", "case 0", '"q"', "not an array")
cases("nan_literal", '{"cases": [{"q": [NaN]}]}', "error", "malformed JSON", "line 1")
cases("infinity_literal", '{"cases": [{"q": [Infinity]}]}', "error", "malformed JSON")
cases("overflow_number", '{"cases": [{"q": [1e400]}]}', "error", "malformed JSON",
      "out of range")
cases("overflowing_result", '{"cases": [{"q": [0.1], "v": [1e300]}]}', "error", "case 0",
      "not finite", "overflow")
cases("empty_file", "", "error", "malformed JSON")
cases("empty_object", "{}", "error", '"cases"')
cases("cases_not_array", '{"cases": {"q": [0]}}', "error", '"cases" is not an array')
cases("case_not_object", '{"cases": [[0.1]]}', "error", "case 0", "not an object")
cases("trailing_garbage", '{"cases": []} extra', "error", "malformed JSON")
cases("no_cases", '{"cases": []}', "ok")
cases("quaternion_not_unit", '{"cases": [{"q": [0, 0, 0, 0, 0, 0, 2, 0.1]}]}', "error",
      "case 0", "root_joint", "quaternion norm", args=FLOAT)
cases("quaternion_zero", '{"cases": [{"q": [0, 0, 0, 0, 0, 0, 0, 0.1]}]}', "error", "case 0",
      "quaternion", args=FLOAT)
cases("huge_angle", '{"cases": [{"q": [1e6], "v": [1e3]}]}', "ok")
cases("unknown_model", '{"cases": []}', "error", "unknown model", '"no_such_robot"',
      args="eval no_such_robot --cases {file}")
cases("floating_builtin", '{"cases": []}', "error", "--floating", "built-in",
      args="eval puma560 --floating --cases {file}")

# ------------------------------------------------------------------- identification samples (CSV)
IDENTIFY = "identify {dir}/../../fixtures/pendulum.urdf --data {file}"


def samples(name, text, status, *contains, args=IDENTIFY):
    write("samples", name, "csv", text, args, status, *contains)


def swing(n, dt=0.01, nan_at=None):
    """rows t, q, v, a, tau of the pendulum swinging (q = sin 2t + 0.5 sin 5t, exact torques:
    tau = 0.51 a + 9.81 sin q)."""
    import math
    rows = ["t,q_hinge,v_hinge,a_hinge,tau_hinge"]
    for k in range(n):
        t = k * dt
        q = math.sin(2 * t) + 0.5 * math.sin(5 * t)
        v = 2 * math.cos(2 * t) + 2.5 * math.cos(5 * t)
        a = -4 * math.sin(2 * t) - 12.5 * math.sin(5 * t)
        tau = 0.51 * a + 9.81 * math.sin(q)
        cells = [t, q, v, a, tau]
        if k == nan_at:
            cells[1] = float("nan")
        rows.append(",".join(repr(x) if isinstance(x, float) else str(x) for x in cells))
    return "\n".join(rows) + "\n"


samples("valid_swing", swing(200), "ok")
samples("nan_row", swing(50, nan_at=7), "error", "line 9", "column 2 (q_hinge)", "NaN",
        "remove the row")
samples("wrong_column_count", "0,0.1,0.2\n0.01,0.1,0.2,0.3,0.4,0.5\n", "error", "line 2",
        "every row needs the same columns")
samples("too_many_columns", "0,1,2,3,4,5,6\n", "error", "line 1", "7 columns", "needs 5")
samples("too_few_samples", swing(2), "error", "2 samples", "3 base parameters",
        "record at least 4 samples")
samples("rank_deficient", "".join(f"{k * 0.01},0.3,0,0,2.899\n" for k in range(100)), "error",
        "excites only", "never move: hinge", "rigid excite")
samples("time_not_increasing", "0,0,0,0,0\n0.1,0,0,0,0\n0.1,0,0,0,0\n", "error", "line 3",
        "column 1 (t)", "does not increase")
samples("header_wrong_joint", "t,q_elbow,v_elbow,a_elbow,tau_elbow\n0,0,0,0,0\n", "error",
        "column 2", "q_elbow", "q_hinge")
samples("word_in_cell", swing(3).replace("0.01,", "zero,", 1), "error", "line 3",
        "column 1 (t)", "not a number")
samples("uneven_time_positions_only", "0,0.1,1\n0.01,0.2,1\n0.05,0.3,1\n0.06,0.4,1\n", "error",
        "line 3", "uniform sampling")
samples("empty", "", "error", "no samples")
samples("mass_tolerance_without_physical", swing(200), "error", "--mass-tolerance", "--physical",
        args=IDENTIFY + " --mass-tolerance 0.2")
samples("out_of_builtin", swing(200), "error", "--out", "built-in",
        args="identify pendulum --data {file} --out {out}")
samples("out_to_missing_folder", swing(200), "error", "/no/such/dir/x.urdf",
        args=IDENTIFY + " --out /no/such/dir/x.urdf")


# ---------------------------------------------------------------------------------------- MJCF
def mjcf(name, text, status, *contains, args="model {file}", extra=None):
    """An MJCF case; `extra` maps other file names of the case (included files) to their text."""
    write("mjcf", name, "xml", text, args, status, *contains)
    for other, content in (extra or {}).items():
        with open(os.path.join(HERE, "mjcf", other), "w") as f:
            f.write(content)


def mujoco(body, head=""):
    return f'<mujoco model="m">\n{head}  <worldbody>\n{body}  </worldbody>\n</mujoco>\n'


ARM = '    <body name="arm" pos="0 0 1">\n      <joint name="hinge" axis="0 1 0"/>\n{}    </body>\n'
CAPSULE = '      <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.05"/>\n'

mjcf("broken_xml", mujoco(ARM.format(CAPSULE)).replace("</body>", "</bod>", 1), "error",
     "malformed XML", "line 6")
mjcf("not_mujoco", '<robot name="r"><link name="a"/></robot>\n', "error", "not <mujoco>")
mjcf("unknown_class", mujoco(ARM.format('      <geom class="nope" size="0.1"/>\n')), "error",
     "line 5", "unknown default class \"nope\"")
mjcf("unknown_childclass", mujoco('    <body childclass="ghost">\n      <geom size="0.1"/>\n'
                                  '    </body>\n'), "error", "line 3", "childclass \"ghost\"")
mjcf("include_loop", mujoco(ARM.format(CAPSULE), '  <include file="include_loop_part.xml"/>\n'),
     "error", "include loop", "include_loop.xml -> include_loop_part.xml -> include_loop.xml",
     extra={"include_loop_part.xml": '<mujoco>\n  <include file="include_loop.xml"/>\n</mujoco>\n'})
mjcf("include_missing", mujoco(ARM.format(CAPSULE), '  <include file="no_such_part.xml"/>\n'),
     "error", "line 2", "no_such_part.xml", "not found")
mjcf("missing_mesh", mujoco(ARM.format('      <geom type="mesh" mesh="m"/>\n'),
                            '  <asset><mesh name="m" file="no_such_mesh.stl"/></asset>\n'),
     "error", "line 2", "mesh \"m\"", "no_such_mesh.stl")
mjcf("mesh_garbage", mujoco(ARM.format('      <geom type="mesh" mesh="m"/>\n'),
                            '  <asset><mesh name="m" file="mesh_garbage.xml"/></asset>\n'),
     "error", "line 2", "unknown mesh file type")
mjcf("fromto_zero_length", mujoco(ARM.format(
    '      <geom type="capsule" fromto="0 0 0.1 0 0 0.1" size="0.05"/>\n')), "error", "line 5",
     "fromto has zero length")
mjcf("negative_geom_mass", mujoco(ARM.format('      <geom size="0.1" mass="-1"/>\n')), "error",
     "line 5", "negative mass")
mjcf("negative_inertial_mass", mujoco(ARM.format(
    '      <inertial pos="0 0 0" mass="-2" diaginertia="1 1 1"/>\n')), "error", "line 5",
     "negative mass")
mjcf("angle_not_finite", mujoco(ARM.format('      <geom type="box" size="0.1 0.1 0.1" '
                                           'euler="1e999 0 0"/>\n')), "error", "line 5",
     "\"euler\" is not finite")
mjcf("mass_overflow", mujoco(ARM.format('      <geom size="1e3" density="1e308"/>\n')), "error",
     "line 5", "not finite")
mjcf("axis_zero", mujoco(ARM.format(CAPSULE).replace('axis="0 1 0"', 'axis="0 0 0"')), "error",
     "line 4", "joint \"hinge\"", "axis is zero")
mjcf("quat_zero", mujoco('    <body quat="0 0 0 0">\n      <geom size="0.1"/>\n    </body>\n'),
     "error", "line 3", "zero quaternion")
mjcf("orientation_twice", mujoco(ARM.format(
    '      <geom type="box" size="0.1 0.1 0.1" quat="1 0 0 0" euler="0 0 10"/>\n')), "error",
     "line 5", "orientation is given twice")
mjcf("joint_type_unknown", mujoco(ARM.format(CAPSULE).replace('axis="0 1 0"', 'type="screw"')),
     "error", "line 4", "\"screw\"", "expected one of")
mjcf("range_reversed", mujoco(ARM.format(CAPSULE).replace('axis="0 1 0"',
                                                          'limited="true" range="1 -1"')),
     "error", "line 4", "range[0] must be smaller")
mjcf("free_joint_below_top", mujoco(ARM.format(
    CAPSULE + '      <body pos="0 0 -0.5">\n        <freejoint/>\n'
              '        <geom size="0.1"/>\n      </body>\n')), "error", "line 7",
     "free joint", "top-level")
mjcf("massless_moving_body", mujoco(ARM.format('')), "error", "line 3", "body \"arm\"",
     "must have mass")
mjcf("size_negative", mujoco(ARM.format('      <geom type="box" size="0.1 -0.1 0.1"/>\n')),
     "error", "line 5", "size[1]", "must be positive")
mjcf("number_garbage", mujoco(ARM.format('      <geom size="0.1" pos="0 zero 0"/>\n')), "error",
     "line 5", "\"pos\"", "\"zero\" is not a number")
mjcf("composite", mujoco('    <body>\n      <composite type="grid" count="2 2 1"/>\n'
                         '    </body>\n'), "error", "line 4", "<composite> is not supported")
mjcf("nested_too_deep", mujoco("".join(f'{" " * (4 + i)}<body pos="0 0 0.1">\n'
                                       for i in range(300))
                                + f'{" " * 304}<geom size="0.01"/>\n'
                                + "".join(f'{" " * (4 + i)}</body>\n' for i in reversed(range(300)))),
     "error", "nested more than 200 deep")
mjcf("inertia_triangle", mujoco(ARM.format(
    '      <inertial pos="0 0 0" mass="1" diaginertia="1 1 3"/>\n')), "error", "line 5",
     "A + B >= C", "balanceinertia")
mjcf("actuators_ignored", mujoco(ARM.format(CAPSULE))
     .replace("</mujoco>", '  <actuator>\n    <motor joint="hinge"/>\n  </actuator>\n</mujoco>'),
     "warning", "line 8", "actuators are not modelled")
mjcf("eval_floating", mujoco(ARM.format(CAPSULE)), "error", "--floating",
     args="model {file} --floating")

# --------------------------------------------------------------------------- command-line args
def cli(name, args, status, *contains):
    write("cli", name, "args", "", args, status, *contains)


RACKET = "{dir}/../../../../examples/racket.toml"
cli("simulate_dt_zero", f"simulate {RACKET} --dt 0 --csv {{out}}", "error", "--dt")
cli("simulate_dt_negative", f"simulate {RACKET} --dt -0.01", "error", "--dt")
cli("simulate_dt_nan", f"simulate {RACKET} --dt nan", "error", "--dt")
cli("simulate_duration_negative", f"simulate {RACKET} --duration -1 --csv {{out}}", "error",
    "--duration")
cli("simulate_duration_infinite", f"simulate {RACKET} --duration inf", "error", "--duration")
cli("simulate_omega_two_numbers", f"simulate {RACKET} --omega 1,2", "error", "--omega")
cli("simulate_omega_words", f"simulate {RACKET} --omega a,b,c", "error", "--omega")
cli("simulate_unknown_integrator", f"simulate {RACKET} --integrator euler", "error", "euler")
cli("simulate_missing_file", "simulate no_such_body.toml", "error", "no_such_body.toml")
cli("mass_missing_file", "mass no_such_body.toml", "error", "no_such_body.toml")
cli("model_unknown", "model no_such_robot", "error", "unknown model", "no_such_robot")
cli("model_missing_file", "model no_such_robot.urdf", "error", "no_such_robot.urdf")
cli("eval_missing_cases_file", "eval puma560 --cases no_such_cases.json", "error",
    "no_such_cases.json")
cli("eval_missing_argument", "eval puma560", "error", "--cases")
cli("bench_floating_builtin", "bench puma560 --floating", "error", "--floating", "built-in")
cli("doctor_missing_file", "doctor no_such_robot.urdf", "error", "no_such_robot.urdf")
cli("doctor_fix_to_missing_folder", "doctor {dir}/../../fixtures/pendulum.urdf --fix /no/such/dir/x.urdf",
    "error", "/no/such/dir/x.urdf")
ROBOT = "{dir}/../../fixtures/pendulum.urdf"
cli("robot_dt_zero", f"simulate {ROBOT} --dt 0 --csv {{out}}", "error", "--dt")
cli("robot_duration_negative", f"simulate {ROBOT} --duration -2 --html {{out}}", "error",
    "--duration")
cli("robot_q0_wrong_length", f"simulate {ROBOT} --q0 0.1,0.2 --duration 0.01", "error", "--q0",
    "1")
cli("robot_q0_nan", f"simulate {ROBOT} --q0 nan --duration 0.01 --csv {{out}}", "error", "--q0")
cli("robot_v0_words", f"simulate {ROBOT} --v0 fast --duration 0.01", "error", "--v0")
cli("robot_unknown_controller", f"simulate {ROBOT} --controller magic", "error", "magic")
cli("robot_pd_without_target", f"simulate {ROBOT} --controller pd --duration 0.01 --csv {{out}}",
    "error", "--target")
cli("robot_target_wrong_length", f"simulate {ROBOT} --controller track --target 1,2 --duration 0.01",
    "error", "--target")
cli("robot_unknown_integrator", f"simulate {ROBOT} --integrator euler --duration 0.01", "error",
    "euler")
cli("robot_plot_unknown_format", f"simulate {ROBOT} --duration 0.01 --plot {{out}}.gif", "error",
    "gif")
cli("robot_body_only_flag", f"simulate {ROBOT} --pivot 0,0,0 --duration 0.01", "error", "--pivot")
cli("robot_unknown_model", "simulate no_such_robot --duration 0.01", "error", "no_such_robot")
cli("robot_output_folder_missing", f"simulate {ROBOT} --duration 0.01 --csv /no/such/dir/x.csv",
    "error", "/no/such/dir/x.csv")
cli("view_q_wrong_length", f"view {ROBOT} --q 1,2,3 --html {{out}}", "error", "--q")
cli("unknown_command", "fly puma560", "error", "fly")
cli("inertia_policy_unknown", "model puma560 --inertia lenient", "error", "lenient")
cli("identify_missing_data", "identify puma560 --data no_such_samples.csv", "error",
    "no_such_samples.csv")
cli("excite_floating", f"excite {ROBOT} --floating --out {{out}}", "error", "root_joint",
    "one degree of freedom")
cli("excite_rate_zero", "excite puma560 --rate 0 --out {out}", "error", "--rate")
cli("excite_duration_nan", "excite puma560 --duration nan --out {out}", "error", "--duration")
cli("excite_missing_folder", "excite pendulum --iterations 2 --duration 1 --out /no/such/dir/t.csv",
    "error", "/no/such/dir/t.csv")

# ----------------------------------------------------------------------------------------- SDF
def sdf(name, body, status, *contains, args="model {file}", version="1.9"):
    text = (f'<?xml version="1.0"?>\n<sdf version="{version}">\n  <model name="m">\n{body}'
            '  </model>\n</sdf>\n')
    write("sdf", name, "sdf", text, args, status, *contains)


SDF_ARM = ('    <link name="arm"><pose>0 0 1 0 0 0</pose><inertial><mass>1</mass></inertial></link>\n'
           '    <joint name="hinge" type="revolute"><parent>world</parent><child>arm</child>\n'
           '      <axis><xyz>0 1 0</xyz></axis></joint>\n')
sdf("arm", SDF_ARM, "ok", "nq = 1")
sdf("broken_xml", SDF_ARM.replace("</link>", "</lnk>", 1), "error", "malformed XML")
sdf("parent_unknown", SDF_ARM.replace("<parent>world", "<parent>ghost"), "error", "line 5",
    'joint "hinge"', '"ghost" is not a link')
sdf("child_unknown", SDF_ARM.replace("<child>arm", "<child>ghost"), "error", "line 5",
    'joint "hinge"', 'its child "ghost" is not a link')
sdf("axis_zero", SDF_ARM.replace("0 1 0</xyz>", "0 0 0</xyz>"), "error", "line 6", "axis is zero")
sdf("pose_words", SDF_ARM.replace("0 0 1 0 0 0", "0 0 one 0 0 0"), "error", "line 4",
    'link "arm" <pose>', "not numbers")
sdf("pose_short", SDF_ARM.replace("0 0 1 0 0 0", "0 0 1 0 0"), "error", "expected 6 numbers")
sdf("pose_relative_to_nothing", SDF_ARM.replace("<pose>", '<pose relative_to="ghost">'), "error",
    '"arm"', '"ghost", which is not defined')
sdf("pose_cycle", SDF_ARM + '    <frame name="f" attached_to="g"/>\n'
    '    <frame name="g" attached_to="f"/>\n', "error", "relative to itself")
sdf("name_clash", SDF_ARM + '    <frame name="arm" attached_to="hinge"/>\n', "error", "line 7",
    'frame "arm"', "already taken by the element at line 4")
sdf("frame_relative_to_nothing", SDF_ARM + '    <frame name="f" attached_to="ghost"/>\n', "error",
    "line 7", '"f"', '"ghost", which is not defined')
sdf("gearbox_not_a_coupling", SDF_ARM + '    <link name="r"><inertial><mass>1</mass></inertial></link>\n'
    '    <joint name="ir" type="revolute"><parent>world</parent><child>r</child>'
    '<axis><xyz>0 1 0</xyz></axis></joint>\n'
    '    <joint name="g" type="gearbox"><parent>r</parent><child>arm</child>'
    '<gearbox_reference_body>arm</gearbox_reference_body><gearbox_ratio>2</gearbox_ratio>'
    '<axis><xyz>0 1 0</xyz></axis><axis2><xyz>0 1 0</xyz></axis2></joint>\n', "ok",
    'joint "g"', '"r" is not turned by a revolute joint from "arm"')
sdf("mass_negative", SDF_ARM.replace("<mass>1</mass>", "<mass>-2</mass>"), "error", "line 4",
    "negative mass")
sdf("joint_type_unknown", SDF_ARM.replace('type="revolute"', 'type="hinge"'), "error",
    '"hinge" is not supported')
sdf("screw_without_pitch", SDF_ARM.replace('type="revolute"', 'type="screw"'), "error",
    "screw_thread_pitch")
sdf("include_missing", SDF_ARM + '    <include><uri>model://no_such_model</uri></include>\n', "error",
    "line 7", '"model://no_such_model" not found')
sdf("loop_prismatic", SDF_ARM + '    <link name="b"><inertial><mass>1</mass></inertial></link>\n'
    '    <joint name="j2" type="revolute"><parent>world</parent><child>b</child>'
    '<axis><xyz>1 0 0</xyz></axis></joint>\n'
    '    <joint name="slide" type="prismatic"><parent>arm</parent><child>b</child>'
    '<axis><xyz>1 0 0</xyz></axis></joint>\n', "ok", 'joint "slide": closes a loop')
sdf("loop_only", '    <link name="a"><inertial><mass>1</mass></inertial></link>\n'
    '    <link name="b"><inertial><mass>1</mass></inertial></link>\n'
    '    <joint name="ab" type="revolute"><parent>a</parent><child>b</child></joint>\n'
    '    <joint name="ba" type="revolute"><parent>b</parent><child>a</child></joint>\n', "error",
    "not reachable")
sdf("two_models", SDF_ARM + '  </model>\n  <model name="second">\n', "error", "several models")
sdf("cylinder_no_length", SDF_ARM.replace("<inertial>", '<collision name="c"><geometry>'
    '<cylinder><radius>0.1</radius></cylinder></geometry></collision><inertial>'), "error",
    "length must be positive")

print("corpus written:", sum(len([f for f in fs if not f.endswith(".expect")])
                              for _, _, fs in os.walk(HERE)) - 1, "files")
