"""Open3D interop (Debian's python3-open3d): boxes as OrientedBoundingBox, a scene as a LineSet.

    import smql, smql.open3d
    db = smql.connect("room.smql")
    boxes = smql.open3d.oriented_boxes(db.execute("FIND chair").boxes())
    lines = smql.open3d.scene_lines(db)          # every box of the scene, coloured by category
    open3d.visualization.draw_geometries([lines, *boxes])
"""
import colorsys
import zlib

import numpy
import open3d


def _rotation(yaw):
    c, s = numpy.cos(yaw), numpy.sin(yaw)
    return numpy.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def category_colour(category):
    """A stable RGB colour (0..1) per category name."""
    hue = (zlib.crc32(category.encode()) % 360) / 360
    return colorsys.hls_to_rgb(hue, 0.55, 0.55)


def oriented_boxes(boxes, colours=None):
    """open3d.geometry.OrientedBoundingBox for each row of an (N, 7) array (Cursor.boxes()):
    centre x, y, z, size x, y, z, yaw about +z."""
    out = []
    for i, (cx, cy, cz, sx, sy, sz, yaw) in enumerate(numpy.asarray(boxes, dtype=float).reshape(-1, 7)):
        box = open3d.geometry.OrientedBoundingBox(numpy.array([cx, cy, cz]), _rotation(yaw), numpy.array([sx, sy, sz]))
        if colours is not None:
            box.color = numpy.asarray(colours[i], dtype=float)
        out.append(box)
    return out


def scene_lines(connection, scene=None, statement="FIND node"):
    """One LineSet of the twelve edges of every box `statement` finds in `scene` (default: the
    current one), each coloured by its category."""
    if scene is not None:
        connection.executescript("USE SCENE '" + scene.replace("'", "''") + "'")
    cursor = connection.execute(statement)
    boxes, categories = cursor.boxes(), cursor.column("category")
    drawn = ~numpy.isnan(boxes).any(axis=1)  # nodes without a box (the scene's own node)
    lines = open3d.geometry.LineSet()
    for box, category in zip(oriented_boxes(boxes[drawn]), numpy.array(categories, dtype=object)[drawn]):
        edges = open3d.geometry.LineSet.create_from_oriented_bounding_box(box)
        edges.paint_uniform_color(category_colour(category))
        lines += edges
    return lines
