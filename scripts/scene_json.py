"""Writes a scene document as the built-in scenes are laid out: one top-level key per line (in the
document's order), then one body per line, so diffs of generated scenes stay readable. Shared by
the scripts/generate_*_scenes.py generators."""
import json
import os


def write_scene(document, directory):
    lines = ["{"]
    for key in document:
        if key != "bodies":
            lines.append(f"  {json.dumps(key)}: {json.dumps(document[key])},")
    lines.append('  "bodies": [')
    bodies = document["bodies"]
    for index, body in enumerate(bodies):
        comma = "," if index + 1 < len(bodies) else ""
        lines.append(f"    {json.dumps(body)}{comma}")
    lines.append("  ]")
    lines.append("}")
    path = os.path.join(directory, document["name"] + ".json")
    with open(path, "w", encoding="utf-8") as out:
        out.write("\n".join(lines) + "\n")
    print(f"wrote {path} ({len(bodies)} bodies, {document['steps']} steps)")
