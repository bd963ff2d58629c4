#!/usr/bin/env python3
"""The heavy benchmark scene's variants used in docs/performance.md (tops48, moving48).

Usage: python3 tools/heavy_variants.py HEAVY_MI [OUT_DIR]

HEAVY_MI is a scene written by ../shared/bench/heavy_scene.py (e.g. heavy_4M.mi); the
variants are written beside it (or into OUT_DIR):

  heavy_mix.mi     the room's mesh once more, as `Room2_obj`, instanced twice out of view
                   (5 and 9 m behind the box): the top level holds triangles, the sphere's
                   quads and instances.
  heavy_inst.mi    the room itself instanced a second time out of view (its mesh shared).
  heavy_move.mi    the sphere's instance slides 20 mm along x while the shutter is open
                   (`motion transform`, `motion on`, `shutter 0 1`).
  heavy_deform.mi  the sphere's vertices carry a motion vector (20 0 0) instead: the
                   same slide as a deformation (`vertex N p n m`).

Everything is derived by text edits; running it twice gives the same files.
"""

import os
import sys

OPTIONS = 'options "Options"\n'
ROOT_END = '    "Sphere_inst"\nend instgroup'
ROOT_MARK = '#\n# The root group'


def instance(name, obj, z):
    return (f'instance "{name}" "{obj}"\n    material [ "white", "green", "red" ]\n    transform\n'
            f'        1 0 0 0\n        0 1 0 0\n        0 0 1 0\n        0 0 {z} 1\nend instance\n\n')


def with_motion_options(text):
    return text.replace(OPTIONS, OPTIONS + '    motion on\n    shutter 0 1\n', 1)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    src_path = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else os.path.dirname(os.path.abspath(src_path))
    text = open(src_path).read()
    for needle in (OPTIONS, ROOT_END, ROOT_MARK, 'object "Room_obj"', 'instance "Sphere_inst" "Sphere_obj"'):
        if needle not in text:
            sys.exit(f"{src_path}: not a heavy_scene.py scene (no {needle!r})")
    root = text.rindex(ROOT_MARK)
    a = text.index('object "Room_obj"')
    room2 = text[a:text.index('end object', a) + len('end object\n')].replace('"Room_obj"', '"Room2_obj"')

    mix = text[:root] + room2 + '\n' + instance('Room_inst2', 'Room2_obj', 5000) + \
        instance('Room_inst3', 'Room2_obj', 9000) + text[root:]
    mix = mix.replace(ROOT_END, '    "Sphere_inst"\n    "Room_inst2"\n    "Room_inst3"\nend instgroup')
    inst = text[:root] + instance('Room_inst2', 'Room_obj', 5000) + text[root:]
    inst = inst.replace(ROOT_END, '    "Sphere_inst"\n    "Room_inst2"\nend instgroup')

    s = text.index('instance "Sphere_inst" "Sphere_obj"')
    e = text.index('end instance', s)
    move = text[:e] + '    motion transform\n        1 0 0 0\n        0 1 0 0\n        0 0 1 0\n        -20 0 0 1\n' + text[e:]
    move = with_motion_options(move)

    # The sphere's vertex rows gain a motion vector.
    o = text.index('object "Sphere_obj"')
    v = text.index('vertex', o)
    v_end = text.index('\n', v)
    if not text[v:v_end].rstrip().endswith('p n'):
        sys.exit(f"{src_path}: the sphere's vertices are not 'p n'")
    rows_start = text.index('[\n', v_end) + 2
    rows_end = text.index(']', rows_start)
    rows = text[rows_start:rows_end].split('\n')
    # Every row but the closing bracket's indentation.
    moved_rows = '\n'.join(r.rstrip() + ' 20 0 0' if r.strip() else r for r in rows)
    deform = text[:v_end].rstrip() + ' m' + text[v_end:rows_start] + moved_rows + text[rows_end:]
    deform = with_motion_options(deform)

    for name, body in (('heavy_mix.mi', mix), ('heavy_inst.mi', inst), ('heavy_move.mi', move),
                       ('heavy_deform.mi', deform)):
        path = os.path.join(out, name)
        with open(path, 'w') as f:
            f.write(body)
        print(path)


if __name__ == '__main__':
    main()
