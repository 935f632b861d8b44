"""No include runs from a lower layer of the library to a higher one (docs/architecture.md).

The layers, low to high: the vocabulary (include/rotbeam's words shared by every layer), model,
surface, contact, integrators, simulation, io, studies, and on top the command line and the Python
bindings. A header belongs to the layer whose src/ folder holds its .cpp, or, for a header with no
.cpp, to the layer listed below; a header in neither place fails the check, so a new one is placed.

    python3 tests/check_layers.py [SOURCE_DIR]     # exit 1 and one line per upward include
"""
import re
import sys
from pathlib import Path

LAYERS = ["vocabulary", "model", "surface", "contact", "integrators", "simulation", "io", "studies", "top"]
# Headers without a .cpp of their own.
HEADER_LAYERS = {
    "outcome.hpp": "vocabulary", "stop_token.hpp": "vocabulary", "pass_options.hpp": "vocabulary",
    "pass.hpp": "vocabulary", "state.hpp": "vocabulary", "ledger.hpp": "vocabulary",
    "force_record.hpp": "vocabulary", "brush_result.hpp": "vocabulary", "history_window.hpp": "vocabulary",
    "units.hpp": "vocabulary", "version.hpp": "vocabulary", "tip_kinematics.hpp": "model",
    "brush_settings.hpp": "vocabulary", "wear_record.hpp": "vocabulary",
    "detail/csv.hpp": "vocabulary", "detail/parse.hpp": "vocabulary", "detail/progress_clock.hpp": "vocabulary",
    "detail/quadratic_form.hpp": "vocabulary", "detail/diagnostics.hpp": "contact",
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def main(root):
    root = Path(root)
    src = root / "src"
    cpp_layer = {p.stem: p.parent.name for p in src.rglob("*.cpp")}
    problems = []

    def header_layer(name):
        if name in HEADER_LAYERS:
            return HEADER_LAYERS[name]
        stem = Path(name).stem
        if stem in cpp_layer and "/" not in name:
            return cpp_layer[stem]
        problems.append(f"include/rotbeam/{name}: no layer (no src/<layer>/{stem}.cpp and not in HEADER_LAYERS)")
        return None

    files = []
    for h in sorted((root / "include" / "rotbeam").rglob("*.hpp")):
        name = h.relative_to(root / "include" / "rotbeam").as_posix()
        files.append((h, header_layer(name)))
    for f in sorted(src.rglob("*.[ch]pp")):
        files.append((f, f.relative_to(src).parts[0]))
    for f in sorted((root / "apps").rglob("*.[ch]pp")):
        files.append((f, "top"))
    files.append((root / "python" / "bindings.cpp", "top"))

    for path, layer in files:
        if layer is None:
            continue
        for inc in INCLUDE.findall(path.read_text()):
            if inc.startswith("rotbeam/"):
                target = header_layer(inc[len("rotbeam/"):])
            elif (path.parent / inc).exists():
                continue  # a header of the same folder: the same layer
            else:
                continue
            if target is not None and LAYERS.index(target) > LAYERS.index(layer):
                problems.append(f"{path.relative_to(root)} ({layer}) includes rotbeam/{inc[8:]} ({target})")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent))
