"""Every reference in the project points at something in the project (docs/model.md §1).

Checks the sources, the tests, the Python package, the benchmarks, the examples and the documents:
  - no citation of a specification outside the project ("SPEC §4", "SPEC.md");
  - every "model.md §N" (also "§N–§M") names a section of docs/model.md whose heading carries §N;
  - every "docs/NAME.md" named exists.

    python3 tests/check_references.py [SOURCE_DIR]     # exit 1 and one line per broken reference
"""
import re
import sys
from pathlib import Path

FOLDERS = ["src", "include", "apps", "python", "tests", "bench", "examples", "docs", "fuzz", "scripts"]
SUFFIXES = {".cpp", ".hpp", ".py", ".md", ".toml", ".sh", ".txt"}
OUTSIDE = re.compile(r"\bSPEC(?:\.md|\s*§)")
SECTION = re.compile(r"model\.md\)?,? §(\d+)(?:\s*[–-]\s*§(\d+))?")
DOC = re.compile(r"\bdocs/([A-Za-z_-]+\.md)\b")


def main(root):
    root = Path(root)
    model = (root / "docs" / "model.md").read_text()
    sections = {int(n) for n in re.findall(r"^##+ .*?§(\d+)", model, re.M)}
    for heading in re.findall(r"^##+ .*$", model, re.M):
        sections |= {int(n) for n in re.findall(r"§(\d+)", heading)}
    files = [root / "README.md"]
    for folder in FOLDERS:
        files += [p for p in (root / folder).rglob("*") if p.is_file() and p.suffix in SUFFIXES]
    bad = []
    for path in files:
        if path.name == "check_references.py":
            continue
        text = path.read_text(errors="replace")
        for no, line in enumerate(text.splitlines(), 1):
            where = f"{path.relative_to(root)}:{no}"
            if OUTSIDE.search(line):
                bad.append(f"{where}: cites a document outside the project: {line.strip()[:100]}")
            for m in SECTION.finditer(line):
                lo = int(m.group(1))
                hi = int(m.group(2)) if m.group(2) else lo
                for n in range(lo, hi + 1):
                    if n not in sections:
                        bad.append(f"{where}: docs/model.md has no section §{n}")
            for m in DOC.finditer(line):
                if not (root / "docs" / m.group(1)).exists():
                    bad.append(f"{where}: docs/{m.group(1)} does not exist")
    for b in bad:
        print(b)
    print(f"{len(files)} files, {len(bad)} broken references; model.md sections: {sorted(sections)}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent))
