#!/usr/bin/env python3
"""Writes the crafted bad-input corpus for mrgi-render (MRGI issue 18).

Usage: make_corpus.py OUTDIR

Every case is a file (or a directory, FIFO or symlink) in OUTDIR whose name
says what is wrong with it. The generator is deterministic (fixed seeds, no
time, no environment): the same OUTDIR contents on every run. Python 3
standard library only.
"""
import base64
import json
import os
import random
import shutil
import struct
import sys
import zlib

CASES = []


def case(name, data):
    CASES.append((name, data if isinstance(data, bytes) else data.encode("latin-1")))


# --- a sound cube, the base every format's cases start from -----------------
CUBE_P = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_T = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
          (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]
NAN = float("nan")


def fmt(v):
    return "nan" if v != v else repr(float(v)) if isinstance(v, float) else str(v)


# --- PLY --------------------------------------------------------------------
def ply_ascii(points=CUBE_P, tris=CUBE_T, nv=None, nf=None, extra_header=""):
    nv = len(points) if nv is None else nv
    nf = len(tris) if nf is None else nf
    s = "ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\n" \
        "property float z\n%selement face %d\nproperty list uchar int vertex_indices\n" \
        "end_header\n" % (nv, extra_header, nf)
    s += "".join("%s %s %s\n" % tuple(fmt(c) for c in p) for p in points)
    s += "".join("%d %s\n" % (len(t), " ".join(str(i) for i in t)) for t in tris)
    return s


def ply_binary(points=CUBE_P, tris=CUBE_T, nv=None, nf=None, count_type="B", endian="<"):
    nv = len(points) if nv is None else nv
    nf = len(tris) if nf is None else nf
    names = {"B": "uchar", "i": "int", "I": "uint"}
    order = "binary_little_endian" if endian == "<" else "binary_big_endian"
    head = ("ply\nformat %s 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
            "property float z\nelement face %d\nproperty list %s int vertex_indices\n"
            "end_header\n" % (order, nv, nf, names[count_type])).encode()
    body = b"".join(struct.pack(endian + "3f", *p) for p in points)
    for t in tris:
        body += struct.pack(endian + count_type, len(t)) + struct.pack(endian + "%di" % len(t), *t)
    return head + body


def ply_cases():
    case("ply_ok_ascii.ply", ply_ascii())
    case("ply_ok_binary.ply", ply_binary())
    case("ply_ok_bigendian.ply", ply_binary(endian=">"))
    for name, tris in (("index_out_of_range", [(0, 1, 99)]), ("index_negative", [(0, -1, 2)]),
                       ("index_huge", [(0, 1, 2147483647)]), ("index_int_min", [(0, 1, -2147483648)]),
                       ("index_equals_count", [(0, 1, 8)]), ("empty_face", [()])):
        case("ply_ascii_%s.ply" % name, ply_ascii(tris=CUBE_T[:3] + tris))
        if tris[0]:
            case("ply_binary_%s.ply" % name, ply_binary(tris=CUBE_T[:3] + tris))
    case("ply_ascii_list_count_too_big.ply", ply_ascii().replace("\n3 0 2 1\n", "\n200 0 2 1\n"))
    case("ply_binary_list_count_255.ply", ply_binary(tris=[(0, 1, 2)])[:-13] + b"\xff" + b"\0" * 12)
    case("ply_binary_list_count_uint_huge.ply",
         ply_binary(tris=[(0, 1, 2)], count_type="I")[:-16] + struct.pack("<I", 0xFFFFFFF0) + b"\0" * 12)
    case("ply_binary_list_count_int_negative.ply",
         ply_binary(tris=[(0, 1, 2)], count_type="i")[:-16] + struct.pack("<i", -5) + b"\0" * 12)
    case("ply_zero_vertices_with_faces.ply", ply_ascii(points=[], tris=CUBE_T))
    case("ply_zero_vertices_binary.ply", ply_binary(points=[], tris=CUBE_T))
    case("ply_zero_vertices_zero_faces.ply", ply_ascii(points=[], tris=[]))
    case("ply_vertex_count_too_big.ply", ply_ascii(nv=1000))
    case("ply_face_count_too_big.ply", ply_ascii(nf=1000))
    case("ply_binary_vertex_count_huge.ply", ply_binary(nv=2000000000))
    case("ply_binary_face_count_huge.ply", ply_binary(nf=2000000000))
    case("ply_nan_coordinates.ply", ply_ascii(points=[(NAN, 0, 0)] + CUBE_P[1:]))
    case("ply_all_nan.ply", ply_ascii(points=[(NAN, NAN, NAN)] * 8))
    case("ply_inf_coordinates.ply", ply_ascii().replace("1.0 1.0 1.0", "inf 1.0 1.0"))
    case("ply_binary_nan.ply", ply_binary(points=[(NAN, NAN, NAN)] + CUBE_P[1:]))
    case("ply_no_z.ply", ply_ascii().replace("property float z\n", ""))
    case("ply_no_end_header.ply", ply_ascii().replace("end_header\n", ""))
    case("ply_long_header_line.ply", "ply\nformat ascii 1.0\ncomment " + "x" * 3000000 + "\n")
    case("ply_header_no_newline.ply", "ply\nformat ascii 1.0\ncomment " + "y" * 2000000)
    case("ply_text_in_body.ply", ply_ascii().replace("1.0 1.0 1.0", "one one one"))
    case("ply_unknown_type.ply", ply_ascii().replace("property float x", "property quux x"))
    case("ply_list_float_count.ply", ply_ascii().replace("list uchar int", "list float int"))
    case("ply_face_indices_float.ply", ply_ascii().replace("list uchar int", "list uchar float"))
    case("ply_two_vertex_elements.ply", ply_ascii().replace(
        "element face", "element vertex 2\nproperty float x\nelement face"))
    case("ply_points_only.ply", ply_ascii(tris=[]))
    case("ply_points_only_one.ply", ply_ascii(points=[(0, 0, 0)], tris=[]))


# --- OBJ --------------------------------------------------------------------
def obj(points=CUBE_P, faces=None, extra=""):
    faces = [" ".join(str(i + 1) for i in t) for t in CUBE_T] if faces is None else faces
    return "".join("v %s %s %s\n" % tuple(fmt(c) for c in p) for p in points) + extra + \
        "".join("f %s\n" % f for f in faces)


def obj_cases():
    case("obj_ok.obj", obj())
    case("obj_ok_relative.obj", obj(faces=["-8 -6 -7", "-8 -5 -6"]))
    case("obj_ok_normals_uv.obj", obj(extra="vn 0 0 1\nvt 0 0\n", faces=["1/1/1 2/1/1 3/1/1"]))
    bad = {"index_out_of_range": "1 2 99", "index_zero": "0 1 2", "index_negative_beyond": "1 2 -9",
           "index_huge": "1 2 2147483648", "index_int_min": "1 2 -2147483648",
           "index_text": "1 2 x", "texcoord_out_of_range": "1/5 2/5 3/99",
           "normal_out_of_range": "1//7 2//7 3//99", "normal_negative": "1//-4 2//-4 3//-4",
           "one_vertex": "1", "two_vertices": "1 2", "empty_face": "",
           "index_float": "1.5 2 3", "index_overflow": "1 2 99999999999999999999999"}
    for name, f in bad.items():
        case("obj_%s.obj" % name, obj(faces=["1 2 3", f]))
    case("obj_texcoord_no_vt.obj", obj(faces=["1/1 2/1 3/1"]))
    case("obj_normal_no_vn.obj", obj(faces=["1//1 2//1 3//1"]))
    case("obj_zero_vertices_with_faces.obj", obj(points=[]))
    case("obj_zero_vertices.obj", "# nothing\n")
    case("obj_only_comments.obj", "# a\n# b\n\n")
    case("obj_nan_coordinates.obj", obj(points=[(NAN, 0, 0)] + CUBE_P[1:]))
    case("obj_all_nan.obj", obj(points=[(NAN, NAN, NAN)] * 8))
    case("obj_inf.obj", obj().replace("v 1 1 1", "v inf 1 1"))
    case("obj_huge_coordinates.obj", obj().replace("v 1 1 1", "v 1e38 1e38 1e38"))
    case("obj_overflow_coordinates.obj", obj().replace("v 1 1 1", "v 1e400 1 1"))
    case("obj_vertex_two_coords.obj", obj().replace("v 1 1 1", "v 1 1"))
    case("obj_vertex_text.obj", obj().replace("v 1 1 1", "v a b c"))
    case("obj_long_line.obj", "v " + "1" * 3000000 + " 0 0\n" + obj())
    case("obj_no_newline_long.obj", "#" + "z" * 2000000)
    case("obj_points_only.obj", obj(faces=[]))
    case("obj_lines_bad.obj", obj(faces=[]) + "l 1 99\n")
    case("obj_point_bad.obj", obj(faces=[]) + "p 99\n")
    case("obj_mtllib_missing.obj", "mtllib nothere.mtl\nusemtl x\n" + obj())
    case("obj_many_faces_one_vertex.obj", "v 0 0 0\n" + "f 1 1 1\n" * 50)
    case("obj_flat_quad.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n")
    case("obj_degenerate_all.obj", "v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3\n")


# --- legacy VTK -------------------------------------------------------------
def vtk_poly(points=CUBE_P, cells=CUBE_T, npoints=None, ncells=None, size=None, binary=False,
             kind="POLYGONS", tail=""):
    npoints = len(points) if npoints is None else npoints
    ncells = len(cells) if ncells is None else ncells
    size = sum(len(c) + 1 for c in cells) if size is None else size
    if not binary:
        s = "# vtk DataFile Version 3.0\ncube\nASCII\nDATASET POLYDATA\nPOINTS %d float\n" % npoints
        s += "".join("%s %s %s\n" % tuple(fmt(c) for c in p) for p in points)
        s += "%s %d %d\n" % (kind, ncells, size)
        s += "".join("%d %s\n" % (len(c), " ".join(str(i) for i in c)) for c in cells)
        return (s + tail).encode()
    s = b"# vtk DataFile Version 3.0\ncube\nBINARY\nDATASET POLYDATA\nPOINTS %d float\n" % npoints
    s += b"".join(struct.pack(">3f", *p) for p in points) + b"\n"
    s += b"%s %d %d\n" % (kind.encode(), ncells, size)
    s += b"".join(struct.pack(">%di" % (len(c) + 1), len(c), *c) for c in cells) + b"\n"
    return s + tail.encode()


def vtk_ugrid(points=CUBE_P, cells=CUBE_T, types=None, ncells=None, size=None, ntypes=None, tail=""):
    types = [5] * len(cells) if types is None else types
    ncells = len(cells) if ncells is None else ncells
    ntypes = len(types) if ntypes is None else ntypes
    size = sum(len(c) + 1 for c in cells) if size is None else size
    s = "# vtk DataFile Version 3.0\ncube\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS %d float\n" % len(points)
    s += "".join("%s %s %s\n" % tuple(fmt(c) for c in p) for p in points)
    s += "CELLS %d %d\n" % (ncells, size)
    s += "".join("%d %s\n" % (len(c), " ".join(str(i) for i in c)) for c in cells)
    s += "CELL_TYPES %d\n" % ntypes + "".join("%d\n" % t for t in types)
    return s + tail


def vtk_points(dims=(4, 4, 4), npd=None, values=None, kind="STRUCTURED_POINTS", typ="float", ncomp=1,
               spacing="1 1 1"):
    n = dims[0] * dims[1] * dims[2] if npd is None else npd
    values = [float(i % 7) for i in range(max(0, min(n, 4096)) * ncomp)] if values is None else values
    s = "# vtk DataFile Version 3.0\nimage\nASCII\nDATASET %s\nDIMENSIONS %d %d %d\n" % ((kind,) + tuple(dims))
    s += "ORIGIN 0 0 0\nSPACING %s\nPOINT_DATA %d\nSCALARS s %s %d\nLOOKUP_TABLE default\n" % (spacing, n, typ, ncomp)
    s += "\n".join(fmt(v) for v in values) + "\n"
    return s


def vtk_cases():
    case("vtk_ok_poly.vtk", vtk_poly())
    case("vtk_ok_poly_binary.vtk", vtk_poly(binary=True))
    case("vtk_ok_ugrid.vtk", vtk_ugrid())
    case("vtk_ok_image.vtk", vtk_points())
    case("vtk_ok_image_uchar.vtk", vtk_points(typ="unsigned_char", values=[i % 200 for i in range(64)]))
    for b in (False, True):
        p = "vtk_%s_" % ("binary" if b else "ascii")
        case(p + "index_out_of_range.vtk", vtk_poly(cells=CUBE_T[:2] + [(0, 1, 99)], binary=b))
        case(p + "index_negative.vtk", vtk_poly(cells=CUBE_T[:2] + [(0, -1, 2)], binary=b))
        case(p + "index_huge.vtk", vtk_poly(cells=CUBE_T[:2] + [(0, 2147483647, 2)], binary=b))
        case(p + "index_equals_count.vtk", vtk_poly(cells=CUBE_T[:2] + [(0, 8, 2)], binary=b))
        case(p + "cell_count_too_big.vtk", vtk_poly(ncells=100, binary=b))
        case(p + "cell_count_huge.vtk", vtk_poly(ncells=2000000000, size=2000000000, binary=b))
        case(p + "cell_size_too_small.vtk", vtk_poly(size=10, binary=b))
        case(p + "cell_size_too_big.vtk", vtk_poly(size=1000, binary=b))
        case(p + "cell_length_huge.vtk", vtk_poly(cells=[(0, 1, 2)], size=4, binary=b).replace(
            b"\n3 0 1 2\n", b"\n1000 0 1 2\n") if not b else
            vtk_poly(cells=[(0, 1, 2)], binary=b).replace(struct.pack(">i", 3) + struct.pack(">3i", 0, 1, 2),
                                                         struct.pack(">i", 1000) + struct.pack(">3i", 0, 1, 2)))
        case(p + "cell_length_negative.vtk", vtk_poly(cells=[(0, 1, 2)], binary=b).replace(
            b"\n3 0 1 2\n", b"\n-3 0 1 2\n") if not b else
            vtk_poly(cells=[(0, 1, 2)], binary=b).replace(struct.pack(">i", 3) + struct.pack(">3i", 0, 1, 2),
                                                         struct.pack(">i", -3) + struct.pack(">3i", 0, 1, 2)))
        case(p + "point_count_too_big.vtk", vtk_poly(npoints=100, binary=b))
        case(p + "point_count_huge.vtk", vtk_poly(npoints=2000000000, binary=b))
        case(p + "point_count_negative.vtk", vtk_poly(npoints=-8, binary=b))
        case(p + "zero_points_with_cells.vtk", vtk_poly(points=[], binary=b))
        case(p + "nan_points.vtk", vtk_poly(points=[(NAN, 0, 0)] + CUBE_P[1:], binary=b))
        case(p + "lines_bad_index.vtk", vtk_poly(cells=[(0, 99)], kind="LINES", binary=b))
        case(p + "verts_bad_index.vtk", vtk_poly(cells=[(99,)], kind="VERTICES", binary=b))
        case(p + "strips_bad_index.vtk", vtk_poly(cells=[(0, 1, 2, 99)], kind="TRIANGLE_STRIPS", binary=b))
    case("vtk_zero_points.vtk", vtk_poly(points=[], cells=[]))
    case("vtk_point_data_count_wrong.vtk", vtk_poly(tail="POINT_DATA 100\nSCALARS s float 1\nLOOKUP_TABLE default\n1\n2\n"))
    case("vtk_point_data_huge.vtk", vtk_poly(tail="POINT_DATA 2000000000\nSCALARS s float 1\nLOOKUP_TABLE default\n1\n"))
    case("vtk_scalars_ncomp_huge.vtk", vtk_poly(tail="POINT_DATA 8\nSCALARS s float 100000\nLOOKUP_TABLE default\n1\n"))
    case("vtk_scalars_ncomp_zero.vtk", vtk_poly(tail="POINT_DATA 8\nSCALARS s float 0\nLOOKUP_TABLE default\n1\n"))
    case("vtk_lookup_table_huge.vtk", vtk_poly(tail="POINT_DATA 8\nSCALARS s float 1\nLOOKUP_TABLE t\n" +
                                                "0\n" * 8 + "LOOKUP_TABLE t 2000000000\n1 1 1 1\n"))
    case("vtk_cell_data_count_wrong.vtk", vtk_poly(tail="CELL_DATA 1000\nSCALARS c float 1\nLOOKUP_TABLE default\n1\n"))
    case("vtk_normals_short.vtk", vtk_poly(tail="POINT_DATA 8\nNORMALS n float\n0 0 1\n"))
    case("vtk_field_huge.vtk", vtk_poly(tail="FIELD f 1\na 2000000000 2000000000 float\n1\n"))
    case("vtk_ugrid_index_out_of_range.vtk", vtk_ugrid(cells=CUBE_T[:2] + [(0, 1, 99)]))
    case("vtk_ugrid_index_negative.vtk", vtk_ugrid(cells=CUBE_T[:2] + [(0, -5, 1)]))
    case("vtk_ugrid_bad_cell_type.vtk", vtk_ugrid(types=[5] * 11 + [9999]))
    case("vtk_ugrid_cell_type_negative.vtk", vtk_ugrid(types=[5] * 11 + [-1]))
    case("vtk_ugrid_hex_with_3_points.vtk", vtk_ugrid(types=[5] * 11 + [12]))
    case("vtk_ugrid_types_count_short.vtk", vtk_ugrid(ntypes=3, types=[5] * 3))
    case("vtk_ugrid_types_count_long.vtk", vtk_ugrid(ntypes=100))
    case("vtk_ugrid_no_cell_types.vtk", vtk_ugrid().split("CELL_TYPES")[0])
    case("vtk_ugrid_cell_count_huge.vtk", vtk_ugrid(ncells=2000000000, size=2000000000))
    case("vtk_ugrid_zero_points.vtk", vtk_ugrid(points=[]))
    case("vtk_ugrid_tetra_ok.vtk", vtk_ugrid(cells=[(0, 1, 3, 4)], types=[10]))
    case("vtk_ugrid_polyhedron_bad.vtk", vtk_ugrid(cells=[(1, 3, 0, 1, 99)], types=[42]))
    case("vtk_image_huge_dims.vtk", vtk_points(dims=(100000, 100000, 100000), npd=64))
    case("vtk_image_huge_dims_2d.vtk", vtk_points(dims=(2000000, 2000000, 1), npd=64))
    case("vtk_image_negative_dims.vtk", vtk_points(dims=(-4, 4, 4), npd=64))
    case("vtk_image_zero_dims.vtk", vtk_points(dims=(0, 0, 0), npd=0))
    case("vtk_image_short_data.vtk", vtk_points(npd=64, values=[1.0, 2.0]))
    case("vtk_image_point_data_mismatch.vtk", vtk_points(dims=(4, 4, 4), npd=10))
    case("vtk_image_nan_spacing.vtk", vtk_points(spacing="nan 1 1"))
    case("vtk_image_zero_spacing.vtk", vtk_points(spacing="0 0 0"))
    case("vtk_image_nan_values.vtk", vtk_points(values=[NAN] * 64))
    # ironProt.vtk's silent failure: unsigned-char density, zero on the outer surface.
    inner = [0 if 0 in (x, y, z) or 3 in (x, y, z) else 200 for z in range(4) for y in range(4) for x in range(4)]
    case("vtk_image_uchar_zero_surface.vtk", vtk_points(typ="unsigned_char", values=inner))
    case("vtk_image_uchar_ncomp3.vtk", vtk_points(typ="unsigned_char", ncomp=3, values=[i % 250 for i in range(192)]))
    case("vtk_sgrid_huge_dims.vtk", "# vtk DataFile Version 3.0\ng\nASCII\nDATASET STRUCTURED_GRID\n"
         "DIMENSIONS 100000 100000 100000\nPOINTS 8 float\n" + "0 0 0\n" * 8)
    case("vtk_rgrid_huge_dims.vtk", "# vtk DataFile Version 3.0\ng\nASCII\nDATASET RECTILINEAR_GRID\n"
         "DIMENSIONS 100000 100000 100000\nX_COORDINATES 2 float\n0 1\nY_COORDINATES 2 float\n0 1\n"
         "Z_COORDINATES 2 float\n0 1\n")
    case("vtk_sgrid_points_short.vtk", "# vtk DataFile Version 3.0\ng\nASCII\nDATASET STRUCTURED_GRID\n"
         "DIMENSIONS 2 2 2\nPOINTS 8 float\n0 0 0\n")
    case("vtk_bad_version.vtk", "# vtk DataFile Version 99.0\nx\nASCII\nDATASET POLYDATA\n")
    case("vtk_no_dataset.vtk", "# vtk DataFile Version 3.0\nx\nASCII\n")
    case("vtk_unknown_dataset.vtk", "# vtk DataFile Version 3.0\nx\nASCII\nDATASET FOO\n")
    case("vtk_header_only.vtk", "# vtk DataFile Version 3.0\n")
    case("vtk_long_title.vtk", "# vtk DataFile Version 3.0\n" + "t" * 3000000 + "\nASCII\nDATASET POLYDATA\n")
    case("vtk_new_format_bad_offsets.vtk", "# vtk DataFile Version 5.1\nx\nASCII\nDATASET POLYDATA\n"
         "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\n"
         "CONNECTIVITY vtktypeint64\n0 1 2\n".replace("OFFSETS vtktypeint64\n0 3", "OFFSETS vtktypeint64\n0 300"))
    case("vtk_new_format_bad_connectivity.vtk", "# vtk DataFile Version 5.1\nx\nASCII\nDATASET POLYDATA\n"
         "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\n"
         "CONNECTIVITY vtktypeint64\n0 1 77\n")
    case("vtk_new_format_decreasing_offsets.vtk", "# vtk DataFile Version 5.1\nx\nASCII\nDATASET POLYDATA\n"
         "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 3 3\nOFFSETS vtktypeint64\n0 3 1\n"
         "CONNECTIVITY vtktypeint64\n0 1 2\n")
    case("vtk_new_format_ok.vtk", "# vtk DataFile Version 5.1\nx\nASCII\nDATASET POLYDATA\n"
         "POINTS 3 float\n0 0 0 1 0 0 0 1 0\nPOLYGONS 2 3\nOFFSETS vtktypeint64\n0 3\n"
         "CONNECTIVITY vtktypeint64\n0 1 2\n")


# --- VTK XML ----------------------------------------------------------------
def da(name, typ, ncomp, values, fmt_="ascii"):
    comp = ' NumberOfComponents="%d"' % ncomp if ncomp else ""
    if fmt_ == "ascii":
        return '<DataArray type="%s" Name="%s"%s format="ascii">%s</DataArray>\n' % (
            typ, name, comp, " ".join(fmt(v) for v in values))
    code = {"Float32": "f", "Int32": "i", "Int64": "q", "UInt8": "B"}[typ]
    raw = struct.pack("<%d%s" % (len(values), code), *values)
    payload = base64.b64encode(struct.pack("<I", len(raw)) + raw).decode()
    return '<DataArray type="%s" Name="%s"%s format="binary">%s</DataArray>\n' % (typ, name, comp, payload)


def vtp(points=CUBE_P, tris=CUBE_T, np_=None, npolys=None, fmt_="ascii", offsets=None, conn=None):
    np_ = len(points) if np_ is None else np_
    npolys = len(tris) if npolys is None else npolys
    conn = [i for t in tris for i in t] if conn is None else conn
    offsets = [3 * (i + 1) for i in range(len(tris))] if offsets is None else offsets
    return ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n'
            '<PolyData><Piece NumberOfPoints="%d" NumberOfPolys="%d">\n<Points>\n%s</Points>\n<Polys>\n%s%s'
            '</Polys>\n</Piece></PolyData></VTKFile>\n' % (
                np_, npolys, da("Points", "Float32", 3, [c for p in points for c in p], fmt_),
                da("connectivity", "Int64", 0, conn, fmt_), da("offsets", "Int64", 0, offsets, fmt_)))


def vtu(points=CUBE_P, tris=CUBE_T, types=None, ncells=None, conn=None, offsets=None, fmt_="ascii"):
    types = [5] * len(tris) if types is None else types
    ncells = len(tris) if ncells is None else ncells
    conn = [i for t in tris for i in t] if conn is None else conn
    offsets = [3 * (i + 1) for i in range(len(tris))] if offsets is None else offsets
    return ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">\n'
            '<UnstructuredGrid><Piece NumberOfPoints="%d" NumberOfCells="%d">\n<Points>\n%s</Points>\n<Cells>\n'
            '%s%s%s</Cells>\n</Piece></UnstructuredGrid></VTKFile>\n' % (
                len(points), ncells, da("Points", "Float32", 3, [c for p in points for c in p], fmt_),
                da("connectivity", "Int64", 0, conn, fmt_), da("offsets", "Int64", 0, offsets, fmt_),
                da("types", "UInt8", 0, types, fmt_)))


def vti(extent="0 3 0 3 0 3", n=64, typ="Float32", ncomp=1, values=None, spacing="1 1 1"):
    values = [float(i % 5) for i in range(n * ncomp)] if values is None else values
    return ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">\n'
            '<ImageData WholeExtent="%s" Origin="0 0 0" Spacing="%s"><Piece Extent="%s">\n'
            '<PointData Scalars="s">%s</PointData>\n</Piece></ImageData></VTKFile>\n' % (
                extent, spacing, extent, da("s", typ, ncomp, values)))


def vtp_appended(offset_shift=0, declared=None):
    raw = struct.pack("<24f", *[c for p in CUBE_P for c in p])
    conn = struct.pack("<36q", *[i for t in CUBE_T for i in t])
    offs = struct.pack("<12q", *[3 * (i + 1) for i in range(12)])
    blocks = []
    offsets = []
    pos = 0
    for b in (raw, conn, offs):
        size = len(b) if declared is None else declared
        blk = struct.pack("<I", size) + b
        offsets.append(pos)
        blocks.append(blk)
        pos += len(blk)
    head = ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian" '
            'header_type="UInt32">\n<PolyData><Piece NumberOfPoints="8" NumberOfPolys="12">\n'
            '<Points><DataArray type="Float32" NumberOfComponents="3" format="appended" offset="%d"/></Points>\n'
            '<Polys><DataArray type="Int64" Name="connectivity" format="appended" offset="%d"/>\n'
            '<DataArray type="Int64" Name="offsets" format="appended" offset="%d"/></Polys>\n'
            '</Piece></PolyData>\n<AppendedData encoding="raw">\n_' % (
                offsets[0], offsets[1] + offset_shift, offsets[2] + offset_shift))
    return head.encode() + b"".join(blocks) + b"\n</AppendedData>\n</VTKFile>\n"


def xml_cases():
    case("vtp_ok.vtp", vtp())
    case("vtp_ok_binary.vtp", vtp(fmt_="binary"))
    case("vtp_ok_appended.vtp", vtp_appended())
    case("vtu_ok.vtu", vtu())
    case("vti_ok.vti", vti())
    case("vti_ok_uchar.vti", vti(typ="UInt8", values=[i % 256 for i in range(64)]))
    for f in ("ascii", "binary"):
        p = "vtp_%s_" % f
        case(p + "index_out_of_range.vtp", vtp(tris=CUBE_T[:2] + [(0, 1, 99)], fmt_=f))
        case(p + "index_negative.vtp", vtp(tris=CUBE_T[:2] + [(0, -1, 1)], fmt_=f))
        case(p + "index_huge.vtp", vtp(tris=CUBE_T[:2] + [(0, 1, 2 ** 62)], fmt_=f))
        case(p + "offsets_beyond.vtp", vtp(offsets=[3 * (i + 1) for i in range(11)] + [999], fmt_=f))
        case(p + "offsets_decreasing.vtp", vtp(offsets=[3, 6, 2] + [3 * (i + 1) for i in range(3, 12)], fmt_=f))
        case(p + "offsets_negative.vtp", vtp(offsets=[-3] + [3 * (i + 1) for i in range(1, 12)], fmt_=f))
        case(p + "offsets_short.vtp", vtp(offsets=[3, 6], fmt_=f))
        case(p + "polys_count_huge.vtp", vtp(npolys=2000000000, fmt_=f))
        case(p + "points_count_too_big.vtp", vtp(np_=100, fmt_=f))
        case(p + "points_count_huge.vtp", vtp(np_=2000000000, fmt_=f))
        case(p + "zero_points.vtp", vtp(points=[], fmt_=f))
        case(p + "nan_points.vtp", vtp(points=[(NAN, 0, 0)] + CUBE_P[1:], fmt_=f))
        p = "vtu_%s_" % f
        case(p + "index_out_of_range.vtu", vtu(tris=CUBE_T[:2] + [(0, 1, 99)], fmt_=f))
        case(p + "index_negative.vtu", vtu(tris=CUBE_T[:2] + [(0, -7, 1)], fmt_=f))
        case(p + "offsets_beyond.vtu", vtu(offsets=[3 * (i + 1) for i in range(11)] + [999], fmt_=f))
        case(p + "offsets_decreasing.vtu", vtu(offsets=[3, 6, 2] + [3 * (i + 1) for i in range(3, 12)], fmt_=f))
        case(p + "cells_count_huge.vtu", vtu(ncells=2000000000, fmt_=f))
        case(p + "bad_cell_type.vtu", vtu(types=[5] * 11 + [200], fmt_=f))
        case(p + "hex_with_3_points.vtu", vtu(types=[5] * 11 + [12], fmt_=f))
        case(p + "types_short.vtu", vtu(types=[5, 5], fmt_=f))
        case(p + "zero_points.vtu", vtu(points=[], fmt_=f))
    case("vtp_binary_header_size_huge.vtp", vtp(fmt_="binary").replace(
        base64.b64encode(struct.pack("<I", 96))[:4].decode(), base64.b64encode(b"\xff\xff\xff\x7f")[:4].decode(), 1))
    case("vtp_bad_base64.vtp", vtp(fmt_="binary").replace("format=\"binary\">", "format=\"binary\">!!!!", 1))
    case("vtp_appended_offset_beyond.vtp", vtp_appended(offset_shift=100000))
    case("vtp_appended_offset_negative.vtp", vtp_appended(offset_shift=-100000))
    case("vtp_appended_block_size_huge.vtp", vtp_appended(declared=0x7FFFFFF0))
    case("vtp_appended_truncated.vtp", vtp_appended()[:-200])
    case("vtp_unclosed.vtp", '<VTKFile type="PolyData"><PolyData><Piece NumberOfPoints="5">')
    case("vtp_not_xml.vtp", "this is not xml at all\n")
    case("vtp_wrong_type.vtp", vtp().replace('type="PolyData"', 'type="Nonsense"', 1))
    case("vtp_points_2_components.vtp", vtp().replace('NumberOfComponents="3"', 'NumberOfComponents="2"'))
    case("vtp_points_0_components.vtp", vtp().replace('NumberOfComponents="3"', 'NumberOfComponents="0"'))
    case("vtp_points_huge_components.vtp", vtp().replace('NumberOfComponents="3"', 'NumberOfComponents="2000000000"'))
    case("vtp_unknown_array_type.vtp", vtp().replace('type="Float32"', 'type="Float99"'))
    case("vtp_deep_nesting.vtp", "<a>" * 100000 + "</a>" * 100000)
    case("vtp_long_attribute.vtp", '<VTKFile type="PolyData" x="' + "q" * 2000000 + '"></VTKFile>')
    case("vti_huge_extent.vti", vti(extent="0 99999 0 99999 0 99999"))
    case("vti_huge_extent_2d.vti", vti(extent="0 999999 0 999999 0 0"))
    case("vti_inverted_extent.vti", vti(extent="3 0 3 0 3 0"))
    case("vti_extent_int_overflow.vti", vti(extent="-2147483648 2147483647 0 3 0 3"))
    case("vti_extent_short.vti", vti(extent="0 3 0 3"))
    case("vti_data_short.vti", vti(values=[1.0, 2.0]))
    case("vti_nan_spacing.vti", vti(spacing="nan 1 1"))
    case("vti_zero_spacing.vti", vti(spacing="0 0 0"))
    case("vti_nan_values.vti", vti(values=[NAN] * 64))
    case("vti_rgb_uchar.vti", vti(typ="UInt8", ncomp=3, values=[(i * 7) % 256 for i in range(192)]))
    case("vts_huge_extent.vts", '<?xml version="1.0"?>\n<VTKFile type="StructuredGrid" version="0.1">'
         '<StructuredGrid WholeExtent="0 99999 0 99999 0 99999"><Piece Extent="0 99999 0 99999 0 99999">'
         '<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">0 0 0</DataArray></Points>'
         '</Piece></StructuredGrid></VTKFile>\n')
    case("vtr_huge_extent.vtr", '<?xml version="1.0"?>\n<VTKFile type="RectilinearGrid" version="0.1">'
         '<RectilinearGrid WholeExtent="0 99999 0 99999 0 99999"><Piece Extent="0 99999 0 99999 0 99999">'
         '<Coordinates><DataArray type="Float32" format="ascii">0 1</DataArray>'
         '<DataArray type="Float32" format="ascii">0 1</DataArray><DataArray type="Float32" format="ascii">0 1'
         '</DataArray></Coordinates></Piece></RectilinearGrid></VTKFile>\n')
    case("vtm_missing_block.vtm", '<?xml version="1.0"?>\n<VTKFile type="vtkMultiBlockDataSet" version="1.0">'
         '<vtkMultiBlockDataSet><DataSet index="0" file="nothere.vtp"/></vtkMultiBlockDataSet></VTKFile>\n')
    case("vtm_self_reference.vtm", '<?xml version="1.0"?>\n<VTKFile type="vtkMultiBlockDataSet" version="1.0">'
         '<vtkMultiBlockDataSet><DataSet index="0" file="vtm_self_reference.vtm"/></vtkMultiBlockDataSet>'
         '</VTKFile>\n')


# --- glTF -------------------------------------------------------------------
def gltf_doc(index_bytes=None, pos_count=8, idx_count=36, view_len=None, buf_len=None, uri=True,
             extra=None, idx_offset=0):
    pos = struct.pack("<24f", *[c for p in CUBE_P for c in p])
    idx = struct.pack("<36H", *[i for t in CUBE_T for i in t]) if index_bytes is None else index_bytes
    data = pos + idx
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data) if buf_len is None else buf_len}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos),
                         "byteLength": len(idx) if view_len is None else view_len}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": pos_count, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 1]},
                      {"bufferView": 1, "byteOffset": idx_offset, "componentType": 5123, "count": idx_count,
                       "type": "SCALAR"}],
    }
    if uri:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    if extra:
        extra(doc)
    return doc, data


def gltf(**kw):
    return json.dumps(gltf_doc(**kw)[0], sort_keys=True)


def glb(doc_data, json_len=None, bin_len=None, total=None, cut=None):
    doc, data = doc_data
    doc["buffers"][0].pop("uri", None)
    js = json.dumps(doc, sort_keys=True).encode()
    js += b" " * (-len(js) % 4)
    data += b"\0" * (-len(data) % 4)
    body = struct.pack("<II", len(js) if json_len is None else json_len, 0x4E4F534A) + js
    body += struct.pack("<II", len(data) if bin_len is None else bin_len, 0x004E4942) + data
    out = struct.pack("<III", 0x46546C67, 2, 12 + len(body) if total is None else total) + body
    return out if cut is None else out[:cut]


def gltf_cases():
    def setter(path, value):
        def f(doc):
            d = doc
            for k in path[:-1]:
                d = d[k]
            d[path[-1]] = value
        return f

    case("gltf_ok.gltf", gltf())
    case("glb_ok.glb", glb(gltf_doc()))
    case("gltf_accessor_count_huge.gltf", gltf(idx_count=2000000000))
    case("gltf_accessor_count_negative.gltf", gltf(idx_count=-1))
    case("gltf_position_count_huge.gltf", gltf(pos_count=1 << 40))
    case("gltf_accessor_offset_beyond.gltf", gltf(idx_offset=100000))
    case("gltf_view_beyond_buffer.gltf", gltf(view_len=100000))
    case("gltf_buffer_length_huge.gltf", gltf(buf_len=1 << 50))
    case("gltf_buffer_length_short.gltf", gltf(buf_len=10))
    case("gltf_buffer_length_negative.gltf", gltf(buf_len=-5))
    case("gltf_index_out_of_range.gltf", gltf(index_bytes=struct.pack("<36H", *([0, 1, 999] * 12))))
    case("gltf_no_uri.gltf", gltf(uri=False))
    case("gltf_missing_uri_file.gltf", gltf(extra=setter(["buffers", 0, "uri"], "nothere.bin")))
    case("gltf_uri_directory.gltf", gltf(extra=setter(["buffers", 0, "uri"], ".")))
    case("gltf_uri_dev_zero.gltf", gltf(extra=setter(["buffers", 0, "uri"], "/dev/zero")))
    case("gltf_bad_data_uri.gltf", gltf(extra=setter(["buffers", 0, "uri"], "data:application/octet-stream;base64,!!!")))
    case("gltf_node_self_cycle.gltf", gltf(extra=setter(["nodes"], [{"mesh": 0, "children": [0]}])))
    case("gltf_node_cycle_2.gltf", gltf(extra=setter(["nodes"], [{"mesh": 0, "children": [1]}, {"children": [0]}])))
    case("gltf_node_child_out_of_range.gltf", gltf(extra=setter(["nodes"], [{"mesh": 0, "children": [5]}])))
    case("gltf_node_mesh_out_of_range.gltf", gltf(extra=setter(["nodes"], [{"mesh": 7}])))
    case("gltf_scene_node_out_of_range.gltf", gltf(extra=setter(["scenes"], [{"nodes": [3]}])))
    case("gltf_scene_index_out_of_range.gltf", gltf(extra=setter(["scene"], 4)))
    case("gltf_no_meshes.gltf", gltf(extra=lambda d: (d.pop("meshes"), d["nodes"][0].pop("mesh"))))
    case("gltf_empty_meshes.gltf", gltf(extra=lambda d: (setter(["meshes"], [])(d), d["nodes"][0].pop("mesh"))))
    case("gltf_no_primitives.gltf", gltf(extra=setter(["meshes"], [{"primitives": []}])))
    case("gltf_attribute_out_of_range.gltf", gltf(extra=setter(["meshes", 0, "primitives", 0, "attributes", "POSITION"], 9)))
    case("gltf_indices_out_of_range.gltf", gltf(extra=setter(["meshes", 0, "primitives", 0, "indices"], 9)))
    case("gltf_view_buffer_out_of_range.gltf", gltf(extra=setter(["bufferViews", 0, "buffer"], 3)))
    case("gltf_accessor_view_out_of_range.gltf", gltf(extra=setter(["accessors", 0, "bufferView"], 8)))
    case("gltf_accessor_bad_type.gltf", gltf(extra=setter(["accessors", 0, "type"], "VEC9")))
    case("gltf_accessor_bad_component.gltf", gltf(extra=setter(["accessors", 0, "componentType"], 1)))
    case("gltf_byte_stride_huge.gltf", gltf(extra=setter(["bufferViews", 0, "byteStride"], 1 << 30)))
    case("gltf_no_buffers.gltf", gltf(extra=lambda d: d.pop("buffers")))
    case("gltf_no_accessors.gltf", gltf(extra=lambda d: d.pop("accessors")))
    case("gltf_image_missing.gltf", gltf(extra=lambda d: d.update(
        images=[{"uri": "nothere.png"}], textures=[{"source": 0}],
        materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])))
    case("gltf_texture_source_out_of_range.gltf", gltf(extra=lambda d: d.update(
        textures=[{"source": 5}], materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}])))
    case("gltf_material_out_of_range.gltf", gltf(extra=setter(["meshes", 0, "primitives", 0, "material"], 4)))
    case("gltf_skin_bad.gltf", gltf(extra=lambda d: (d.update(skins=[{"joints": [9]}]), d["nodes"][0].update(skin=0))))
    case("gltf_animation_bad.gltf", gltf(extra=lambda d: d.update(animations=[{
        "samplers": [{"input": 9, "output": 9}], "channels": [{"sampler": 0, "target": {"node": 9, "path": "translation"}}]}])))
    case("gltf_wrong_types.gltf", gltf(extra=setter(["accessors", 0, "count"], "eight")))
    case("gltf_null_everything.gltf", json.dumps({"asset": None, "meshes": None, "nodes": None}))
    case("gltf_not_json.gltf", "{ this is not json")
    case("gltf_empty_object.gltf", "{}")
    case("gltf_deep_nesting.gltf", "[" * 200000 + "]" * 200000)
    case("gltf_json_array.gltf", "[1, 2, 3]")
    case("gltf_long_string.gltf", '{"asset": {"version": "2.0", "x": "' + "s" * 2000000 + '"}}')
    case("gltf_sparse_bad.gltf", gltf(extra=setter(["accessors", 0, "sparse"], {
        "count": 1000, "indices": {"bufferView": 1, "componentType": 5123}, "values": {"bufferView": 0}})))
    case("gltf_nan_positions.gltf", gltf(extra=setter(["buffers", 0, "uri"], "data:application/octet-stream;base64," +
                                                       base64.b64encode(struct.pack("<24f", *([NAN] * 24)) +
                                                                        struct.pack("<36H", *[i for t in CUBE_T for i in t])).decode())))
    case("glb_bin_chunk_length_huge.glb", glb(gltf_doc(), bin_len=0x7FFFFFF0))
    case("glb_json_chunk_length_huge.glb", glb(gltf_doc(), json_len=0x7FFFFFF0))
    case("glb_total_length_huge.glb", glb(gltf_doc(), total=0x7FFFFFF0))
    case("glb_total_length_short.glb", glb(gltf_doc(), total=20))
    case("glb_truncated.glb", glb(gltf_doc(), cut=100))
    case("glb_truncated_bin.glb", glb(gltf_doc(), cut=-40))
    case("glb_buffer_longer_than_bin.glb", glb(gltf_doc(buf_len=5000)))
    case("glb_accessor_count_huge.glb", glb(gltf_doc(idx_count=2000000000)))
    case("glb_node_cycle.glb", glb(gltf_doc(extra=setter(["nodes"], [{"mesh": 0, "children": [0]}]))))
    case("glb_bad_magic.glb", b"glTX" + glb(gltf_doc())[4:])
    case("glb_version_1.glb", glb(gltf_doc())[:4] + struct.pack("<I", 1) + glb(gltf_doc())[8:])
    case("glb_header_only.glb", glb(gltf_doc())[:12])


# --- LAS point clouds and vertex-only clouds (issue 15) ---------------------
def las(points=CUBE_P, minor=2, fmt=3, scale=0.001, offset=(500000.0, 5400000.0, 0.0), count=None,
        header_size=None, offset_to_points=None, record=None, format_byte=None):
    """A LAS file from the ASPRS specification: points in metres, classes 2 and 5, RGB."""
    lengths = {0: 20, 1: 28, 2: 26, 3: 34, 6: 30, 7: 36}
    size = 375 if minor >= 4 else 227
    rec = lengths[fmt]
    h = bytearray(size)
    h[0:4] = b"LASF"
    h[24], h[25] = 1, minor
    n = len(points) if count is None else count
    struct.pack_into("<HIIBHI", h, 94, size if header_size is None else header_size,
                     size if offset_to_points is None else offset_to_points,
                     0, fmt if format_byte is None else format_byte, rec if record is None else record,
                     0 if minor >= 4 else n & 0xFFFFFFFF)
    if minor >= 4:
        struct.pack_into("<Q", h, 247, n)
    struct.pack_into("<3d3d", h, 131, scale, scale, scale, *offset)
    body = bytearray()
    for i, p in enumerate(points):
        r = bytearray(rec)
        struct.pack_into("<3iH", r, 0, *[int(round(p[c] / 0.001)) for c in range(3)], 100 * i)
        r[14] = 0x09
        r[16 if fmt >= 6 else 15] = 2 if i % 2 else 5
        rgb = {2: 20, 3: 28, 7: 30}.get(fmt)
        if rgb is not None:
            struct.pack_into("<3H", r, rgb, 60000, 30000 + 1000 * i, 5000)
        body += r
    return bytes(h) + bytes(body)


def las_cases():
    case("las_ok_format3.las", las())
    case("las_ok_format6_14.las", las(minor=4, fmt=6))
    case("las_ok_format0.las", las(fmt=0))
    case("las_one_point.las", las(points=[(1, 2, 3)]))
    case("las_laz_compressed.laz", las(format_byte=3 | 0x80))
    case("las_laz_named_las.las", las(format_byte=3 | 0x80))
    case("las_signature.las", b"LASX" + las()[4:])
    case("las_version_2_0.las", las()[:24] + b"\x02\x00" + las()[26:])
    case("las_header_size_small.las", las(header_size=10))
    case("las_header_size_huge.las", las(header_size=65535))
    case("las_points_offset_outside.las", las(offset_to_points=0x7FFFFFF0))
    case("las_points_offset_in_header.las", las(offset_to_points=4))
    case("las_format_11.las", las(format_byte=11))
    case("las_record_short.las", las(record=4))
    case("las_count_zero.las", las(count=0))
    case("las_count_huge.las", las(count=0xFFFFFFFF))
    case("las_count64_huge.las", las(minor=4, fmt=6, count=(1 << 63) - 1))
    case("las_scale_zero.las", las(scale=0.0))
    case("las_scale_nan.las", las(scale=NAN))
    case("las_scale_huge.las", las(scale=1e300))
    case("las_offset_inf.las", las(offset=(float("inf"), 0.0, 0.0)))
    case("las_header_only.las", las()[:227])
    # Vertex-only clouds: NaN points left out, all-NaN refused.
    nan_points = [(NAN, NAN, NAN)] * 8
    case("ply_points_all_nan.ply", ply_binary(points=nan_points, tris=[]))
    case("ply_points_some_nan.ply", ply_binary(points=CUBE_P[:4] + nan_points, tris=[]))
    case("vtk_points_all_nan.vtk", vtk_poly(points=nan_points, cells=[(i,) for i in range(8)], binary=True,
                                            kind="VERTICES"))


# --- generic: garbage, truncation, empty ------------------------------------
EXTS = [".ply", ".obj", ".vtk", ".vtp", ".vtu", ".vti", ".vts", ".vtr", ".vtm", ".stl", ".gltf", ".glb",
        ".las", ".laz", ".pcd"]


def generic_cases():
    rng = random.Random(18)
    for ext in EXTS:
        case("empty" + ext, b"")
        case("garbage" + ext, bytes(rng.getrandbits(8) for _ in range(4096)))
        case("zeros" + ext, b"\0" * 4096)
        case("newlines" + ext, b"\n" * 4096)
    # Truncations of the sound files, at a few fixed fractions.
    sound = [(n, d) for n, d in CASES if "_ok" in n]
    for name, data in sound:
        stem, ext = os.path.splitext(name)
        for frac in (0.1, 0.5, 0.9):
            case("truncated_%d_%s%s" % (int(frac * 100), stem, ext), data[:int(len(data) * frac)])
        # One flipped byte in the middle (deterministic).
        flipped = bytearray(data)
        flipped[len(data) // 2] ^= 0x5A
        case("flipped_%s%s" % (stem, ext), bytes(flipped))
    case("stl_ascii_ok.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
         "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n")
    case("stl_binary_count_huge.stl", b"\0" * 80 + struct.pack("<I", 2000000000) + b"\0" * 50)
    case("stl_nan.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 1 0 0\n"
         "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n")
    case("unknown_extension.xyz", "1 2 3\n")
    case("no_extension", "1 2 3\n")


def main():
    if len(sys.argv) != 2:
        sys.stderr.write(__doc__)
        return 2
    out = sys.argv[1]
    if os.path.isdir(out):
        shutil.rmtree(out)
    os.makedirs(out)
    ply_cases()
    obj_cases()
    vtk_cases()
    xml_cases()
    gltf_cases()
    las_cases()
    generic_cases()
    names = set()
    for name, data in CASES:
        assert name not in names, name
        names.add(name)
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    # Things that are not regular files.
    for ext in (".ply", ".obj", ".vtk", ".vtp", ".gltf"):
        os.makedirs(os.path.join(out, "directory" + ext))
        os.mkfifo(os.path.join(out, "fifo" + ext))
        os.symlink("/dev/zero", os.path.join(out, "dev_zero" + ext))
        os.symlink("does-not-exist" + ext, os.path.join(out, "dangling" + ext))
    os.symlink("/dev/null", os.path.join(out, "dev_null.ply"))
    os.symlink("ply_ok_ascii.ply", os.path.join(out, "symlink_ok.ply"))
    print("%d cases in %s" % (len(os.listdir(out)), out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
