#!/usr/bin/python3
"""Renders glTF 2.0 files (.glb or .gltf with embedded buffers) side by side
into one PNG, textures included: a small software rasterizer (numpy, PIL),
so that a repaired asset can be compared with its input by eye without a
GPU or a browser.

    bench/render_gltf.py in.glb out.glb --out pair.png [--size 480] [--view 1,0.6,1.4]

Each panel is an orthographic view along -VIEW of one file, all panels
framed on the first file's bounding box, shaded by base colour (factor x
texture at TEXCOORD_0) x (0.35 + 0.65 |n . light|). Draco-compressed
primitives are not decoded (write the output without --draco)."""

import argparse
import base64
import io
import json
import struct
import sys

import numpy as np
from PIL import Image, ImageDraw

COMPONENTS = {5120: np.int8, 5121: np.uint8, 5122: np.int16, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


def load(path):
    data = open(path, "rb").read()
    if data[:4] == b"glTF":
        length = struct.unpack_from("<I", data, 12)[0]
        doc = json.loads(data[20:20 + length])
        rest = 20 + length
        binary = data[rest + 8:rest + 8 + struct.unpack_from("<I", data, rest)[0]] if rest < len(data) else b""
    else:
        doc, binary = json.loads(data), b""
    buffers = []
    for b in doc.get("buffers", []):
        uri = b.get("uri")
        buffers.append(base64.b64decode(uri.split(",", 1)[1]) if uri else binary)
    return doc, buffers


def view_bytes(doc, buffers, index):
    v = doc["bufferViews"][index]
    start = v.get("byteOffset", 0)
    return buffers[v["buffer"]][start:start + v["byteLength"]], v.get("byteStride")


def accessor(doc, buffers, index):
    a = doc["accessors"][index]
    dtype, width, count = COMPONENTS[a["componentType"]], WIDTH[a["type"]], a["count"]
    raw, stride = view_bytes(doc, buffers, a["bufferView"])
    item = np.dtype(dtype).itemsize * width
    stride = stride or item
    offset = a.get("byteOffset", 0)
    rows = np.frombuffer(raw, np.uint8, count=(count - 1) * stride + item, offset=offset)
    rows = np.lib.stride_tricks.as_strided(rows, (count, item), (stride, 1))
    out = np.frombuffer(rows.copy().tobytes(), dtype).reshape(count, width).astype(np.float64)
    if a.get("normalized") and dtype != np.float32:
        out /= np.iinfo(dtype).max
    return out


def node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], np.float64).reshape(4, 4).T
    t = np.eye(4)
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    t[:3, :3] = r * np.array(node.get("scale", [1, 1, 1]))
    t[:3, 3] = node.get("translation", [0, 0, 0])
    return t


def texture_image(doc, buffers, material):
    info = material.get("pbrMetallicRoughness", {}).get("baseColorTexture")
    if not info or info.get("texCoord", 0) != 0:
        return None
    image = doc["images"][doc["textures"][info["index"]]["source"]]
    if "bufferView" in image:
        raw = view_bytes(doc, buffers, image["bufferView"])[0]
    elif image.get("uri", "").startswith("data:"):
        raw = base64.b64decode(image["uri"].split(",", 1)[1])
    else:
        return None
    return np.asarray(Image.open(io.BytesIO(raw)).convert("RGBA"), np.float64) / 255.0


def triangles(path):
    """Every triangle primitive, in world coordinates: (positions, faces, uvs or None, material dict, image)."""
    doc, buffers = load(path)
    parts = []

    def visit(index, parent):
        node = doc["nodes"][index]
        world = parent @ node_matrix(node)
        for p in doc["meshes"][node["mesh"]]["primitives"] if "mesh" in node else []:
            if p.get("mode", 4) != 4 or "extensions" in p:
                continue
            pos = accessor(doc, buffers, p["attributes"]["POSITION"])
            pos = pos @ world[:3, :3].T + world[:3, 3]
            faces = (accessor(doc, buffers, p["indices"]).astype(np.int64).reshape(-1, 3) if "indices" in p
                     else np.arange(len(pos)).reshape(-1, 3))
            uv = accessor(doc, buffers, p["attributes"]["TEXCOORD_0"]) if "TEXCOORD_0" in p["attributes"] else None
            material = doc["materials"][p["material"]] if "material" in p else {}
            parts.append((pos, faces, uv, material, texture_image(doc, buffers, material) if uv is not None else None))
        for child in node.get("children", []):
            visit(child, world)

    scene = doc.get("scenes", [{}])[doc.get("scene", 0)]
    for root in scene.get("nodes", []):
        visit(root, np.eye(4))
    return parts


def camera(view):
    back = np.asarray(view, np.float64)
    back /= np.linalg.norm(back)
    right = np.cross([0.0, 1.0, 0.0], back)
    right = right / np.linalg.norm(right) if np.linalg.norm(right) > 1e-9 else np.array([1.0, 0.0, 0.0])
    return np.stack([right, np.cross(back, right), back])  # rows: screen x, screen y, towards the viewer


def render(parts, rotation, frame, size):
    lo, scale = frame
    color = np.ones((size, size, 3))
    depth = np.full((size, size), -np.inf)
    light = np.array([0.3, 0.5, 1.0]) / np.linalg.norm([0.3, 0.5, 1.0])
    for pos, faces, uv, material, image in parts:
        eye = pos @ rotation.T
        screen = np.empty_like(eye[:, :2])
        screen[:, 0] = (eye[:, 0] - lo[0]) * scale
        screen[:, 1] = size - 1 - (eye[:, 1] - lo[1]) * scale
        factor = np.asarray(material.get("pbrMetallicRoughness", {}).get("baseColorFactor", [1, 1, 1, 1]))[:3]
        for face in faces:
            draw_triangle(face, screen, eye, uv, image, factor, light, color, depth)
    return Image.fromarray((np.clip(color, 0, 1) * 255).astype(np.uint8))


def draw_triangle(face, screen, eye, uv, image, factor, light, color, depth):
    a, b, c = screen[face]
    normal = np.cross(eye[face[1]] - eye[face[0]], eye[face[2]] - eye[face[0]])
    length = np.linalg.norm(normal)
    area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    if length == 0 or area == 0:
        return
    shade = 0.35 + 0.65 * abs(normal @ light) / length
    x0, x1 = int(max(np.floor(min(a[0], b[0], c[0])), 0)), int(min(np.ceil(max(a[0], b[0], c[0])), depth.shape[1] - 1))
    y0, y1 = int(max(np.floor(min(a[1], b[1], c[1])), 0)), int(min(np.ceil(max(a[1], b[1], c[1])), depth.shape[0] - 1))
    if x0 > x1 or y0 > y1:
        return
    ys, xs = np.mgrid[y0:y1 + 1, x0:x1 + 1] + 0.5
    w1 = ((xs - a[0]) * (c[1] - a[1]) - (ys - a[1]) * (c[0] - a[0])) / area
    w2 = ((b[0] - a[0]) * (ys - a[1]) - (b[1] - a[1]) * (xs - a[0])) / area
    w0 = 1 - w1 - w2
    inside = (w0 >= 0) & (w1 >= 0) & (w2 >= 0)
    z = w0 * eye[face[0], 2] + w1 * eye[face[1], 2] + w2 * eye[face[2], 2]
    region = depth[y0:y1 + 1, x0:x1 + 1]
    front = inside & (z > region)
    if not front.any():
        return
    region[front] = z[front]
    rgb = np.broadcast_to(factor, front.shape + (3,)).copy()
    if image is not None:
        t = w0[..., None] * uv[face[0]] + w1[..., None] * uv[face[1]] + w2[..., None] * uv[face[2]]
        h, w = image.shape[:2]
        px = np.mod(np.floor(t[..., 0] * w), w).astype(int)
        py = np.mod(np.floor(t[..., 1] * h), h).astype(int)
        rgb = rgb * image[py, px, :3]
    color[y0:y1 + 1, x0:x1 + 1][front] = rgb[front] * shade


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--out", required=True)
    parser.add_argument("--size", type=int, default=480)
    parser.add_argument("--view", default="1,0.6,1.4", help="direction the camera looks from (x,y,z)")
    args = parser.parse_args()
    rotation = camera([float(v) for v in args.view.split(",")])
    scenes = [triangles(f) for f in args.files]
    eye = np.concatenate([p[0] for p in scenes[0]]) @ rotation.T
    lo, hi = eye.min(axis=0), eye.max(axis=0)
    extent = max(hi[0] - lo[0], hi[1] - lo[1]) * 1.08
    lo = (lo + hi) / 2 - extent / 2
    panels = [render(parts, rotation, (lo, (args.size - 1) / extent), args.size) for parts in scenes]
    sheet = Image.new("RGB", (args.size * len(panels), args.size + 22), "white")
    draw = ImageDraw.Draw(sheet)
    for i, (panel, name) in enumerate(zip(panels, args.files)):
        sheet.paste(panel, (i * args.size, 22))
        draw.text((i * args.size + 6, 5), name.rsplit("/", 1)[-1], fill="black")
    sheet.save(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
