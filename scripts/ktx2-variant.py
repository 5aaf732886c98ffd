#!/usr/bin/env python3
"""Writes a KTX2 (KHR_texture_basisu) variant of a .gltf asset whose images are files: each
image encoded by Binomial's `basisu` (ETC1S or UASTC), with the transfer function its slots
need (sRGB for colour, linear for data), the textures pointed at it through the extension.
With `gltfmat compare SOURCE VARIANT` it shows what the compression changes on screen.

Usage: scripts/ktx2-variant.py SOURCE.gltf OUT_FOLDER [--uastc]   (BASISU=path/to/basisu)
"""
import json, os, pathlib, shutil, subprocess, sys

COLOUR_SLOTS = {"baseColorTexture", "emissiveTexture", "sheenColorTexture", "specularColorTexture",
                "diffuseTransmissionColorTexture", "diffuseTexture", "specularGlossinessTexture"}


def slot_spaces(doc):
    """Texture index → 'srgb' or 'linear', from the first slot that reads it."""
    spaces = {}

    def walk(value, key=None):
        if isinstance(value, dict):
            if key and key.endswith("Texture") and "index" in value:
                spaces.setdefault(value["index"], "srgb" if key in COLOUR_SLOTS else "linear")
            for k, v in value.items():
                walk(v, k)
        elif isinstance(value, list):
            for v in value:
                walk(v)

    walk(doc.get("materials", []))
    return spaces


def main():
    source, out = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    uastc = "--uastc" in sys.argv[3:]
    basisu = os.environ.get("BASISU", "basisu")
    out.mkdir(parents=True, exist_ok=True)
    doc = json.loads(source.read_text())
    spaces = slot_spaces(doc)
    image_space = {}
    for index, texture in enumerate(doc.get("textures", [])):
        if "source" in texture:
            image_space.setdefault(texture["source"], spaces.get(index, "srgb"))
    for buffer in doc.get("buffers", []):
        if "uri" in buffer and not buffer["uri"].startswith("data:"):
            shutil.copy(source.parent / buffer["uri"], out / buffer["uri"])
    for index, image in enumerate(doc.get("images", [])):
        name = pathlib.Path(image["uri"]).with_suffix(".ktx2").name
        options = ["-uastc", "-uastc_level", "2"] if uastc else ["-q", "255"]
        if image_space.get(index) == "linear":
            options.append("-linear")
        subprocess.run([basisu, "-ktx2", "-mipmap", *options, str(source.parent / image["uri"]),
                        "-output_file", str(out / name)], check=True, stdout=subprocess.DEVNULL)
        image["uri"] = name
        image.pop("mimeType", None)
    for texture in doc.get("textures", []):
        if "source" in texture:
            texture.setdefault("extensions", {})["KHR_texture_basisu"] = {"source": texture.pop("source")}
    for key in ("extensionsUsed", "extensionsRequired"):
        doc[key] = sorted(set(doc.get(key, [])) | {"KHR_texture_basisu"})
    (out / source.name).write_text(json.dumps(doc, indent=1) + "\n")


if __name__ == "__main__":
    main()
