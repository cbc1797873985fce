"""The gallery: examples/*.py run by sphinx-gallery, as they are.

The example scripts are written to be run from a shell (argparse, their
docstring as the help text, __file__ for the files beside them) and their
docstrings are plain text, not reStructuredText. So the build does not point
sphinx-gallery at examples/ itself: configuration() writes one gallery source
per script into build/docs-gallery-src/, made of

- the script's docstring turned into reST (a title from its first sentence,
  prose paragraphs escaped, indented blocks kept as literal blocks),
- two hidden lines that give the script its own __file__ and __doc__,
- the rest of the script, unchanged (the code the page shows is the
  example's code),

and sphinx-gallery runs those in build/docs-gallery-src/ with __name__ ==
"__main__" and the command line of reset_argv: ``--plot NAME.png`` (and
``--picture NAME-picture.png``) for the scripts that take them, ``--plot``
for cart_pole.py (a pyplot figure). png_scraper puts the PNG files a script
wrote on its page; pyplot figures come through sphinx-gallery's matplotlib
scraper. A script ends with sys.exit(main()), which would end the whole
build (SystemExit): while a script runs, sys.exit returns on 0 and raises
RuntimeError on anything else (reset_exit). A gallery source is rewritten
only when it changes, so sphinx-gallery's own cache (the MD5 of each source)
reruns only what changed.
"""

import ast
import glob
import os
import re
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLES = os.path.join(ROOT, "examples")
SOURCES = os.path.join(ROOT, "build", "docs-gallery-src")

#: the options of the scripts that write figures, in the order their images show
FIGURE_OPTIONS = ("picture", "plot")

HEADER = """\
Gallery
=======

Every script in ``examples/`` run when these pages were built, with its
printed output and the figures it drew. Each page shows the script's code as
it is; run it yourself with ``python examples/NAME.py`` (``--help`` lists its
options) after ``make demo``. The figures come from the script's own
options: ``--picture PATH`` draws the mechanism at one moment with the paths
its points travelled (first: the page's thumbnail), ``--plot PATH`` its time
histories.

The scenes in ``examples/*.toml`` are run with ``lagmb run SCENE`` (see
:doc:`/tour`): seed pendulum, double pendulum, slider-crank, four-bar,
quick return, gear train, spring-damper, bouncing ball, rolling disk, cam
follower, Andrews' squeezer, N-four-bar, cart-pole (with an input, for
``lagmb fmu``) and the heavy top (``heavy_top.toml``, spatial).
"""

#: the gallery's order: the simplest first, then by what they show
ORDER = ("seed_pendulum", "double_pendulum", "spring_damper", "four_bar", "slider_crank", "quick_return",
         "gear_train", "bouncing_ball", "door_stop", "rolling_disk", "cam_follower", "incline", "andrews",
         "n_four_bar", "cart_pole", "panda", "go1_drop", "mjcf_four_bar")


class ExampleOrder:
    """sphinx-gallery's within_subsection_order: ORDER, then the other
    scripts by name."""

    def __init__(self, src_dir):
        self.src_dir = src_dir

    def __call__(self, filename):
        stem = os.path.splitext(os.path.basename(filename))[0]
        return (ORDER.index(stem), "") if stem in ORDER else (len(ORDER), stem)

    def __repr__(self):
        return "ExampleOrder"


def _escape(text):
    """Plain text as reST shows it: markup characters escaped, except
    inside ``literal`` spans, which stay literals."""
    parts = re.split(r"(``[^`]+``)", text)
    return "".join(part if k % 2 else re.sub(r"([\\`*|_])", r"\\\1", part) for k, part in enumerate(parts))


def _title(first):
    """The page title: the first sentence up to its first ': ' or ' (', and
    up to its first ', ' if still longer than 60 characters."""
    for seps in ((": ", " ("), (", ",)):
        for sep in seps:
            k = first.find(sep)
            if k > 0:
                first = first[:k]
        if len(first) <= 60:
            break
    return first.rstrip(".")


def rst_docstring(text, stem, argv):
    """The docstring of examples/<stem>.py as the reST of its gallery page."""
    blocks = [b for b in re.split(r"\n[ \t]*\n", text.strip("\n")) if b.strip()]
    first = " ".join(line.strip() for line in blocks[0].splitlines())
    title = _title(first)
    out = [title + "\n" + "=" * len(title), _escape(first)]
    for block in blocks[1:]:
        lines = block.splitlines()
        if all(line.startswith(" ") for line in lines):
            if out[-1].endswith(":") and not out[-1].endswith("::"):
                out[-1] += ":"
            else:
                out.append("::")
            out.append(block)
        elif lines[0].startswith("- ") and all(line.startswith(("- ", "  ")) for line in lines):
            out.append("\n".join(_escape(line) for line in lines))
        elif any(line.startswith(" ") for line in lines):
            out.append("::")
            out.append("\n".join("    " + line for line in lines))
        else:
            out.append(_escape(" ".join(line.strip() for line in lines)))
    command = " ".join(["python", f"examples/{stem}.py", *argv])
    out.append(f"Source: :download:`examples/{stem}.py <../../examples/{stem}.py>`; "
               f"this page ran ``{command}``.")
    return "\n\n".join(out) + "\n"


def _figure_file(stem, option):
    """The PNG a script writes for one of FIGURE_OPTIONS, in the folder it
    runs in (sphinx-gallery runs it in SOURCES)."""
    return f"{stem}.png" if option == "plot" else f"{stem}-{option}.png"


def argv_for(source, stem):
    """The command-line arguments the gallery runs examples/<stem>.py with."""
    argv = []
    for option in FIGURE_OPTIONS:
        if re.search(rf"add_argument\(\s*\"--{option}\",\s*metavar=\"PATH\"", source):
            argv += [f"--{option}", _figure_file(stem, option)]
    if re.search(r"\"--plot\" in sys\.argv|add_argument\(\s*\"--plot\",\s*action=\"store_true\"", source):
        argv += ["--plot"]  # a pyplot figure the scraper collects
    return argv


def gallery_source(path):
    """The gallery source of one example script (text)."""
    source = open(path, encoding="utf-8").read()
    stem = os.path.splitext(os.path.basename(path))[0]
    tree = ast.parse(source)
    doc = ast.get_docstring(tree, clean=True)
    if doc is None:
        raise ValueError(f"{path}: an example starts with a docstring (its gallery page's text)")
    body = source.splitlines(keepends=True)[tree.body[0].end_lineno:]
    argv = argv_for(source, stem)
    return "".join([
        '"""\n', rst_docstring(doc, stem, argv), '"""\n',
        "# sphinx_gallery_start_ignore\n",
        f"__file__ = {path!r}\n",
        f"__doc__ = {ast.get_docstring(tree, clean=False)!r}\n",
        "# sphinx_gallery_end_ignore\n",
        *body,
    ])


def write_sources():
    """Writes build/docs-gallery-src/ (only the files that changed)."""
    os.makedirs(SOURCES, exist_ok=True)
    wanted = {"GALLERY_HEADER.rst": HEADER}
    for path in sorted(glob.glob(os.path.join(EXAMPLES, "*.py"))):
        wanted[os.path.basename(path)] = gallery_source(path)
    for name in os.listdir(SOURCES):
        if name not in wanted and os.path.isfile(os.path.join(SOURCES, name)):
            os.remove(os.path.join(SOURCES, name))
    for name, text in wanted.items():
        target = os.path.join(SOURCES, name)
        if not os.path.exists(target) or open(target, encoding="utf-8").read() != text:
            with open(target, "w", encoding="utf-8") as f:
                f.write(text)


def reset_argv(gallery_conf, script_vars):
    """sphinx-gallery's reset_argv: the arguments of the script being run."""
    stem = os.path.splitext(os.path.basename(script_vars["src_file"]))[0]
    source = open(os.path.join(EXAMPLES, stem + ".py"), encoding="utf-8").read()
    for option in FIGURE_OPTIONS:
        png = os.path.join(SOURCES, _figure_file(stem, option))
        if os.path.exists(png):
            os.remove(png)
    return argv_for(source, stem)


def _exit(code=None):
    """sys.exit while an example runs in the build: its last line."""
    if code not in (None, 0):
        raise RuntimeError(f"the example exited with {code!r}")


def reset_exit(gallery_conf, fname, when):
    """sphinx-gallery's reset_modules: sys.exit patched around each example."""
    if when == "before":
        sys.exit = _exit
    else:
        sys.exit = _SYS_EXIT


_SYS_EXIT = sys.exit


def png_scraper(block, block_vars, gallery_conf, **kwargs):
    """The PNG files the script wrote (FIGURE_OPTIONS order) onto its page.
    When it wrote some, its pyplot figures are those files and are closed."""
    from sphinx_gallery.scrapers import figure_rst

    stem = os.path.splitext(os.path.basename(block_vars["src_file"]))[0]
    found = []
    for option in FIGURE_OPTIONS:
        png = os.path.join(SOURCES, _figure_file(stem, option))
        if os.path.exists(png):
            target = next(block_vars["image_path_iterator"])
            shutil.move(png, target)
            found.append(target)
    if found:
        import matplotlib.pyplot as plt
        plt.close("all")
    return figure_rst(found, gallery_conf["src_dir"])


def forget_removed(gallery):
    """Removes from the gallery's output folder the pages of scripts no
    longer in examples/ (their pages would be in no toctree: a warning)."""
    stems = {os.path.splitext(name)[0] for name in os.listdir(EXAMPLES) if name.endswith(".py")}
    if not os.path.isdir(gallery):
        return
    for name in os.listdir(gallery):
        stem = name.split(".")[0]
        path = os.path.join(gallery, name)
        if os.path.isfile(path) and stem != "index" and stem not in stems:
            os.remove(path)


def configuration(docs):
    """sphinx_gallery_conf for docs/conf.py (writes the gallery sources)."""
    write_sources()
    forget_removed(os.path.join(docs, "gallery"))
    return {
        "examples_dirs": SOURCES,
        "gallery_dirs": os.path.join(docs, "gallery"),
        "filename_pattern": r".*\.py$",
        "reset_argv": "gallery_sources.reset_argv",
        "image_scrapers": ("gallery_sources.png_scraper", "matplotlib"),
        "reset_modules": ("matplotlib", "gallery_sources.reset_exit"),
        "reset_modules_order": "both",
        "within_subsection_order": "gallery_sources.ExampleOrder",
        "download_all_examples": False,
        "remove_config_comments": True,
        "abort_on_example_error": True,
        "show_memory": False,
        "min_reported_time": 1e9,
        "line_numbers": False,
        "capture_repr": (),
        "write_computation_times": False,
    }
