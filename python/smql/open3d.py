"""Open3D interop (Debian's python3-open3d): boxes as OrientedBoundingBox, a scene as a LineSet.

    import smql, smql.open3d
    db = smql.connect("room.smql")
    boxes = smql.open3d.oriented_boxes(db.execute("FIND chair").boxes())
    lines = smql.open3d.scene_lines(db)          # every box of the scene, coloured by category
    points = smql.open3d.scene_points(db)        # the capture's coloured points (ingested scenes)
    open3d.visualization.draw_geometries([points, lines, *boxes])

Colours are the engine's: each category in the colour SHOW CATEGORIES gives it, as the view, the
map and the exports draw it.
"""
import numpy
import open3d


def _rotation(yaw):
    c, s = numpy.cos(yaw), numpy.sin(yaw)
    return numpy.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def category_colours(connection):
    """{category: (r, g, b) in 0..1} for the current scene, from SHOW CATEGORIES."""
    return {category: tuple(int(colour[i:i + 2], 16) / 255 for i in (1, 3, 5))
            for category, _, colour in connection.execute("SHOW CATEGORIES").fetchall()}


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


def scene_points(connection, scene=None):
    """The capture's coloured points of `scene` (default: the current one) as an
    open3d.geometry.PointCloud, in the frame of the boxes: what `smql export ply --points` writes."""
    import os
    import tempfile
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "points.ply")
        connection.export(path, format="ply", scene=scene, points=True)
        return open3d.io.read_point_cloud(path)


def scene_lines(connection, scene=None, statement="FIND node"):
    """One LineSet of the twelve edges of every box `statement` finds in `scene` (default: the
    current one), each coloured by its category."""
    if scene is not None:
        connection.executescript("USE SCENE '" + scene.replace("'", "''") + "'")
    colours = category_colours(connection)
    cursor = connection.execute(statement)
    boxes, categories = cursor.boxes(), cursor.column("category")
    drawn = ~numpy.isnan(boxes).any(axis=1)  # nodes without a box (the scene's own node)
    lines = open3d.geometry.LineSet()
    for box, category in zip(oriented_boxes(boxes[drawn]), numpy.array(categories, dtype=object)[drawn]):
        edges = open3d.geometry.LineSet.create_from_oriented_bounding_box(box)
        edges.paint_uniform_color(numpy.asarray(colours.get(category, (0.5, 0.5, 0.5)), dtype=float))
        lines += edges
    return lines
