# Sphinx configuration of the LSDEM documentation: `./lsdem docs` builds HTML into
# build/doc/html (warnings are errors there and in the test doc.html).
import re

from docutils import nodes
from pygments.lexer import RegexLexer, bygroups
from pygments.token import Comment, Keyword, Name, Number, String, Text

project = "LSDEM"
copyright = "LSDEM developers"
master_doc = "index"
exclude_patterns = ["_build"]
html_theme = "alabaster"
html_static_path = []
# LAMMPS's own pages (pair_coeff, create_atoms, ...) are linked at docs.lammps.org
LAMMPS_DOCS = "https://docs.lammps.org/"


class LammpsLexer(RegexLexer):
    """Input-script highlighting: the command word, comments, variables, numbers, strings
    (LAMMPS's own docs use a lexer of their own, not in Pygments)."""
    name = "LAMMPS"
    aliases = ["LAMMPS", "lammps"]
    tokens = {"root": [
        (r"#.*$", Comment),
        (r"^(\s*)([a-z_/]+)", bygroups(Text, Keyword)),
        (r"\$\{[^}]*\}|\$\([^)]*\)|v_\w+|c_\w+(\[\*?\d*\])?|f_\w+(\[\d+\])?", Name.Variable),
        (r'"[^"]*"|\'[^\']*\'', String),
        (r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", Number),
        (r"\s+|\S", Text),
    ]}


def lammps_page(app, env, node, contnode):
    """A :doc: reference to a page that is not ours is one of LAMMPS's."""
    if node.get("reftype") != "doc":
        return None
    target = node["reftarget"]
    if re.fullmatch(r"[A-Za-z0-9_]+", target) is None or target in env.found_docs:
        return None
    ref = nodes.reference("", "", internal=False, refuri=LAMMPS_DOCS + target + ".html")
    ref.append(contnode)
    return ref


def setup(app):
    app.add_lexer("LAMMPS", LammpsLexer)
    app.connect("missing-reference", lammps_page)
