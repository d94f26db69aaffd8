#!/usr/bin/env python3
"""Check the Fortran style rules of the developers' guide on src/, app/ and test/.

The guide asks for: one module per file, named after it; implicit none; private by default;
an intent on every dummy argument; library code that never stops or prints; no common,
equivalence or goto; FORD doc comments on public procedures; no global mutable state. It also keeps the layers
of docs/architecture.md apart: a src/ module never uses one of a higher layer (LAYERS below).
The compiler enforces none of these, so this script does (it runs in .ci/run). `--list-rules`
lists the rules and the exceptions allowed, `--self-test` proves that each rule can fail.

It reads free-form source as the compiler does: comments (a `!` outside strings), continuation
lines (`&`, also inside strings), `;`-separated statements, any letter case, labels and
construct names, one-line `if (...) action`. It is a checker of the house rules, not a
Fortran parser: it understands the statements this code base uses.

Usage: python3 scripts/check_style.py [--list-rules | --self-test | FILE...]
Prints `path:line: rule: message` per violation and a count; exit status 1 if any.
"""
import argparse
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIRS = ('src', 'app', 'test')
SUFFIXES = ('.f90', '.F90', '.f95', '.f03', '.f08')

# The architecture (docs/architecture.md): every folder src/<layer>/ is a layer, and this table,
# lowest tier first, is the one place that orders them. The layers of one tier are siblings.
# A src/ file may use the modules of its own layer and of every lower tier; using a module of
# a higher tier, or of a sibling unless SIBLING_USES allows the pair, is a `layering`
# violation. test/ and app/ stand above every tier and may use anything. A new src/ folder
# must be added here: its files are reported until it is.
LAYERS = [
    ('core',),                         # kinds, errors, strings, clock, file-name conventions
    ('linalg', 'elements'),            # CSR matrix, LAPACK/BLAS interfaces | element kernels and
                                       # the element catalog
    ('model',),                        # the model's plain data (its groups hold catalog answers)
    ('materials',),                    # constitutive models, built from the model's material specs
    ('input', 'assembly', 'solvers'),  # deck reader | DOFs, stiffness, loads | linear solvers
    ('analysis',),                     # the staged incremental driver and its state
    ('post',),                         # stress recovery, analytical joint models
    ('output',),                       # HDF5 results, XDMF, principal stresses
    ('program',),                      # what the `feps` command does
]
SIBLING_USES = set()                   # (layer, sibling it may use) pairs: none, siblings are independent
TIER = {layer: rank for rank, tier in enumerate(LAYERS) for layer in tier}

RULES = [
    ('one-module', "one module per file, the file named after it (src/ and test/; a file whose "
                   "unit is a program, e.g. app/main.f90 and test/main.f90, needs no name)"),
    ('implicit-none', "`implicit none` in every program unit: module, submodule, program and "
                      "external procedure (module procedures inherit the module's)"),
    ('private-default', "a bare `private` statement in the specification part of every module "
                        "in src/ and test/"),
    ('intent', "every dummy argument of a procedure or interface body declared with an "
               "intent; exceptions: `value` dummies (copied in, intent adds nothing) and "
               "non-pointer procedure dummies (the standard forbids intent on them)"),
    ('no-stop-print', "no stop, error stop, call exit/abort, print or write to *, 6, 0, "
                      "output_unit or error_unit in src/ (the library returns an error_t)"),
    ('legacy', "no common, equivalence, go to, implicit other than `implicit none`, or include"),
    ('doc-comment', "a FORD doc comment (`!>` lines just before the header or a `!!` line just "
                    "after it) on every public procedure of a src/ module: those named public "
                    "(or all, without default private), the generic interfaces named public, "
                    "the procedures bound to public types and the abstract interfaces of their "
                    "deferred bindings (a `!!` after the binding documents it too); a binding that overrides one of a parent type is "
                    "documented there (as FORD shows it) and needs no comment of its own; the "
                    "comment before a one-procedure interface block counts for its procedure; "
                    "anywhere: no `!>` line inside a doc block (a displaced comment)"),
    ('global-state', "no module variable, save or data statement in src/ modules (every "
                     "module-level declaration is a parameter); `protected` does not help: the "
                     "owning module still writes it"),
    ('layering', "a src/ module uses only modules of its own layer (its folder under src/) and of "
                 "lower ones, as the LAYERS table at the top of this script orders them; a sibling "
                 "layer (same tier) only where SIBLING_USES allows it; a src/ folder missing from "
                 "the table is reported; test/ and app/ may use anything"),
]
RULE_NAMES = [name for name, _ in RULES]

PREFIX_WORDS = {'pure', 'elemental', 'impure', 'recursive', 'non_recursive', 'module',
                'integer', 'real', 'complex', 'logical', 'character', 'double', 'precision',
                'type', 'class'}
ATTR_STATEMENT = re.compile(
    r'^(intent\s*\(\s*(?:in|out|inout|in\s+out)\s*\)|value|optional|pointer|target|allocatable|'
    r'external|save|protected|contiguous|volatile|asynchronous|dimension|intrinsic)\s*(::)?\s*'
    r'([a-z_]\w*.*)$')


class Statement:
    """One statement: lower-case code without comments, string contents blanked, continuation
    lines joined; `first` and `last` are its physical lines (1-based)."""

    def __init__(self, code, first, last):
        self.code, self.first, self.last = code, first, last


def statements(lines, trailing_docs=None):
    """Split free-form source into statements (see Statement); the numbers of the lines with
    code and a `!!` doc comment after it go into the set trailing_docs."""
    result = []
    parts, first, quote = [], None, None
    for number, line in enumerate(lines, 1):
        text = line.rstrip('\n').rstrip('\r')
        if first is not None:          # a continuation line
            stripped = text.lstrip()
            if stripped.startswith('&'):
                text = stripped[1:]
            elif quote is None:
                if stripped == '' or stripped.startswith('!'):
                    continue           # comment lines may stand between continued lines
                text = stripped
        out, k, continued = [], 0, False
        while k < len(text):
            c = text[k]
            if quote:
                if c == quote:
                    if text[k + 1:k + 2] == quote:
                        k += 2          # a doubled quote inside the string
                        continue
                    quote = None
                    out.append(c)
                elif c == '&' and text[k + 1:].strip() == '':
                    continued = True
                    break
                k += 1                  # string contents are blanked
                continue
            if c in '\'"':
                quote = c
                out.append(c)
            elif c == '!':
                if text[k:k + 2] == '!!' and ''.join(out).strip() and trailing_docs is not None:
                    trailing_docs.add(number)
                break
            else:
                out.append(c)
            k += 1
        code = ''.join(out).rstrip()
        if not continued and quote is None and code.endswith('&'):
            continued, code = True, code[:-1]
        if first is None:
            if code.strip() == '' and not continued:
                continue
            first = number
        parts.append(code)
        if continued:
            continue
        joined = ' '.join(parts).strip().lower()
        for piece in split_semicolons(joined):
            if piece:
                result.append(Statement(piece, first, number))
        parts, first, quote = [], None, None
    return result


def split_semicolons(code):
    pieces, start, quote = [], 0, None
    for k, c in enumerate(code):
        if quote:
            if c == quote:
                quote = None
        elif c in '\'"':
            quote = c
        elif c == ';':
            pieces.append(code[start:k].strip())
            start = k + 1
    pieces.append(code[start:].strip())
    return pieces


def split_top(text, sep=','):
    """Split at separators outside parentheses and strings."""
    pieces, depth, start, quote = [], 0, 0, None
    for k, c in enumerate(text):
        if quote:
            if c == quote:
                quote = None
        elif c in '\'"':
            quote = c
        elif c in '([':
            depth += 1
        elif c in ')]':
            depth -= 1
        elif c == sep and depth == 0:
            pieces.append(text[start:k].strip())
            start = k + 1
    pieces.append(text[start:].strip())
    return [p for p in pieces if p]


def closing_paren(text, open_at):
    """Index of the parenthesis closing the one at open_at (-1 if none)."""
    depth = 0
    for k in range(open_at, len(text)):
        if text[k] == '(':
            depth += 1
        elif text[k] == ')':
            depth -= 1
            if depth == 0:
                return k
    return -1


def strip_label(code):
    """Without a statement label or a construct name."""
    code = re.sub(r'^\d+\s+', '', code)
    return re.sub(r'^[a-z_]\w*\s*:(?!:)\s*', '', code)


def actions(code):
    """The statement and, for a one-line `if (...) action`, also the action."""
    found = [code]
    m = re.match(r'^if\s*\(', code)
    if m:
        end = closing_paren(code, m.end() - 1)
        rest = code[end + 1:].strip() if end > 0 else ''
        if rest and rest != 'then' and not rest.startswith('then '):
            found.extend(actions(strip_label(rest)))
    return found


def declaration(code):
    """(type keyword, attributes, entity names) of a type declaration statement, or None."""
    m = re.match(r'^(double\s*precision|double\s*complex|integer|real|complex|logical|character|'
                 r'type|class|procedure)\b\s*', code)
    if not m:
        return None
    keyword = re.sub(r'\s+', '', m.group(1))
    k = m.end()
    if k < len(code) and code[k] == '(':
        end = closing_paren(code, k)
        if end < 0:
            return None
        k = end + 1
    elif keyword in ('type', 'class', 'procedure'):
        return None                    # a type definition, `procedure :: x` binding, ...
    rest = code[k:].strip()
    star = re.match(r'^\*\s*(\(\s*[^)]*\)|\d+)\s*', rest)
    if star:
        rest = rest[star.end():]
    attributes = []
    if rest.startswith(','):
        parts = rest[1:].split('::', 1)
        if len(parts) != 2:
            return None
        attributes = [a.strip() for a in split_top(parts[0])]
        rest = parts[1]
    elif rest.startswith('::'):
        rest = rest[2:]
    elif re.match(r'^(function|subroutine)\b', rest) or rest == '' or rest.startswith('='):
        return None
    names = []
    for entity in split_top(rest):
        n = re.match(r'^([a-z_]\w*)', entity)
        if n:
            names.append(n.group(1))
    if not names:
        return None
    return keyword, attributes, names


def attribute_names(attributes):
    """Attribute keywords: 'intent', 'value', 'pointer', 'parameter', ..."""
    return {re.match(r'^[a-z_]+', a).group(0) for a in attributes if re.match(r'^[a-z_]+', a)}


class Scope:
    def __init__(self, kind, name, stmt, parent):
        self.kind, self.name, self.stmt, self.parent = kind, name, stmt, parent
        self.children = []
        self.statements = []           # statements directly in this scope (not its children)
        self.after_contains = False
        self.contains_at = 10 ** 9     # line of the scope's `contains`
        self.implicit_none = False
        self.default_private = False
        self.args, self.result = [], None
        self.abstract = False          # abstract interface
        self.generic = None            # the generic name of an interface block
        self.attrs = ''                # attributes of a type definition


HEADER = re.compile(r'^(?P<prefix>.*?)\b(?P<kind>subroutine|function)\s+(?P<name>[a-z_]\w*)\s*'
                    r'(?P<rest>\(.*)?$')


def procedure_header(code):
    """(kind, name, args, result name) of a subroutine or function statement, or None."""
    m = HEADER.match(code)
    if not m:
        return None
    prefix = re.sub(r'\([^()]*(\([^()]*\)[^()]*)*\)', ' ', m.group('prefix'))
    prefix = re.sub(r'\*\s*\d+', ' ', prefix)
    if not all(word in PREFIX_WORDS for word in prefix.split()):
        return None
    rest = m.group('rest') or ''
    args = []
    if rest.startswith('('):
        end = closing_paren(rest, 0)
        if end < 0:
            return None
        args = [a.strip() for a in rest[1:end].split(',') if a.strip()]
        rest = rest[end + 1:]
    if rest.strip() and not re.match(r'^\s*(result|bind)\s*\(', rest):
        return None
    result = re.search(r'\bresult\s*\(\s*([a-z_]\w*)\s*\)', rest)
    return m.group('kind'), m.group('name'), args, (result.group(1) if result else m.group('name'))


def parse(text):
    """The scope tree of a file: a root scope whose children are the program units."""
    lines = text.split('\n')
    root = Scope('file', '', None, None)
    root.trailing_docs = set()
    stack = [root]
    for stmt in statements(lines, root.trailing_docs):
        code = strip_label(stmt.code)
        stmt.code = code
        top = stack[-1]
        end = re.match(r'^end\s*(subroutine|function|module|submodule|program|interface|type|'
                       r'procedure|block\s*data)?\b', code)
        if end and (end.group(1) or code == 'end'):
            if len(stack) > 1:
                stack.pop()
            continue
        if code == 'contains':
            top.after_contains, top.contains_at = True, stmt.first
            continue
        opened = None
        m = re.match(r'^module\s+([a-z_]\w*)$', code)
        if m and m.group(1) != 'procedure' and top.kind != 'interface':
            opened = Scope('module', m.group(1), stmt, top)
        if not opened:
            m = re.match(r'^submodule\s*\(([^)]*)\)\s*([a-z_]\w*)', code)
            if m:
                opened = Scope('submodule', m.group(2), stmt, top)
        if not opened:
            m = re.match(r'^program\s+([a-z_]\w*)', code)
            if m:
                opened = Scope('program', m.group(1), stmt, top)
        if not opened:
            m = re.match(r'^block\s*data\b\s*(\w*)', code)
            if m:
                opened = Scope('blockdata', m.group(1), stmt, top)
        if not opened:
            m = re.match(r'^(abstract\s+)?interface\b\s*(.*)$', code)
            if m:
                opened = Scope('interface', '', stmt, top)
                opened.abstract = bool(m.group(1))
                opened.generic = m.group(2).replace(' ', '') or None
        if not opened and top.kind not in ('interface',):
            m = (re.match(r'^type\s*(?:,(?P<attrs>.*?))?::\s*(?P<name>[a-z_]\w*)', code)
                 or re.match(r'^type\s+(?P<name>[a-z_]\w*)\s*$', code))
            if m and m.group('name') != 'is':
                opened = Scope('type', m.group('name'), stmt, top)
                opened.attrs = (m.groupdict().get('attrs') or '').replace(' ', '')
        if not opened and top.kind in ('submodule', 'module') and top.after_contains:
            m = re.match(r'^module\s+procedure\s+([a-z_]\w*)$', code)
            if m:
                opened = Scope('mprocedure', m.group(1), stmt, top)
        if not opened:
            header = procedure_header(code)
            if header:
                kind, name, args, result = header
                opened = Scope(kind, name, stmt, top)
                opened.args, opened.result = args, result
        if opened:
            top.children.append(opened)
            stack.append(opened)
            continue
        top.statements.append(stmt)
        if re.match(r'^implicit\s+none\b', code):
            top.implicit_none = True
        if code == 'private' and not top.after_contains:
            top.default_private = True
    return root, lines


def walk(scope):
    yield scope
    for child in scope.children:
        yield from walk(child)


def is_doc(line):
    s = line.strip()
    return s.startswith('!>') or s.startswith('!!')


def documented(lines, stmt, trailing_docs=()):
    """A doc comment line just before stmt or just after it, or `!!` after its code."""
    before = lines[stmt.first - 2] if stmt.first >= 2 else ''
    after = lines[stmt.last] if stmt.last < len(lines) else ''
    return (is_doc(before) or after.strip().startswith('!!')
            or any(n in trailing_docs for n in range(stmt.first, stmt.last + 1)))


def check_source(path, text, index=None, layers=None):
    """Violations (line, rule, message) of one file; path is relative to the package root,
    index (see type_index) knows the types of the other files, for inherited bindings, and
    layers (see module_layers) the layer of every module, for the layering rule."""
    path = path.replace(os.sep, '/')
    area = path.split('/', 1)[0]
    in_src = area == 'src'
    root, lines = parse(text)
    found = []

    def report(line, rule, message):
        found.append((line, rule, message))

    units = root.children
    modules = [u for u in units if u.kind == 'module']
    stem = os.path.splitext(os.path.basename(path))[0].lower()
    # one-module
    if len(units) > 1:
        report(units[1].stmt.first, 'one-module',
               '%d program units in one file (%s); one module per file'
               % (len(units), ', '.join('%s %s' % (u.kind, u.name) for u in units)))
    if in_src and not modules:
        report(1, 'one-module', 'no module in a src/ file')
    for module in modules[:1]:
        if module.name != stem:
            report(module.stmt.first, 'one-module',
                   'module %s in file %s.f90 (name the file after the module)' % (module.name, stem))
    # implicit-none
    for unit in units:
        if not unit.implicit_none:
            report(unit.stmt.first, 'implicit-none', '%s %s has no `implicit none`' % (unit.kind, unit.name))
    # private-default
    for module in modules:
        if area in ('src', 'test') and not module.default_private:
            report(module.stmt.first, 'private-default',
                   'module %s has no bare `private` statement (private by default)' % module.name)

    for scope in walk(root):
        for stmt in scope.statements:
            for code in actions(stmt.code):
                # no-stop-print
                if in_src:
                    m = (re.match(r'^(error\s*stop|stop)\b(?!\s*=)', code)
                         or re.match(r'^print\b(?!\s*=)', code)
                         or re.match(r'^call\s+(exit|abort)\b', code)
                         or re.match(r'^write\s*\(\s*(unit\s*=\s*)?(\*|6|0|output_unit|error_unit)\s*[,)]', code))
                    if m:
                        report(stmt.first, 'no-stop-print',
                               '`%s` in library code: return an error_t instead' % ' '.join(code.split()[:2])[:40])
                # legacy
                if re.match(r'^common\b\s*[/a-z]', code):
                    report(stmt.first, 'legacy', 'common block')
                if re.match(r'^equivalence\s*\(', code):
                    report(stmt.first, 'legacy', 'equivalence')
                if re.match(r'^go\s*to\b\s*[\d(a-z]', code):
                    report(stmt.first, 'legacy', 'go to')
                if re.match(r'^implicit\b', code) and not re.match(r'^implicit\s+none\b', code):
                    report(stmt.first, 'legacy', 'implicit typing (`%s`): only `implicit none`' % code[:40])
                if re.match(r'^include\s*[\'"]', code):
                    report(stmt.first, 'legacy', 'include of Fortran source: use a module')

    for number in range(2, len(lines) + 1):
        if lines[number - 1].strip().startswith('!>') and is_doc(lines[number - 2]):
            report(number, 'doc-comment', 'a second `!>` in one doc block: FORD gives both to the next '
                   'entity (continue with `!!`, or the first documents something else)')
    for scope in walk(root):
        if scope.kind in ('subroutine', 'function'):
            check_intents(scope, report)
    if in_src:
        for module in modules:
            check_module_state(module, report)
            check_docs(module, lines, root.trailing_docs, report, dict(index or {}, **type_index(root)))
        check_layering(path, root, dict(layers or {}, **module_layers(path, root)), report)
    return sorted(found)


USE = re.compile(r'^use\b\s*(?:,\s*(intrinsic|non_intrinsic)\s*)?(?:::)?\s*([a-z_]\w*)')


def path_layer(path):
    """The layer of a file: its folder under src/ ('' for a file directly in src/), else
    the top folder (test, app)."""
    parts = path.replace(os.sep, '/').split('/')
    if parts[0] == 'src':
        return parts[1] if len(parts) > 2 else ''
    return parts[0]


def layer_rank(layer):
    """The tier of a layer in LAYERS; test/ and app/ above them all; None if unknown."""
    return len(LAYERS) if layer in ('test', 'app') else TIER.get(layer)


def module_layers(path, root):
    """{module name: layer} of the modules a file defines."""
    return {unit.name: path_layer(path) for unit in root.children if unit.kind == 'module'}


def check_layering(path, root, layers, report):
    """The src/ file at path uses no module of a higher or a forbidden sibling layer (LAYERS)."""
    layer = path_layer(path)
    if layer not in TIER:
        report(1, 'layering', '%s is in no layer: add its folder to the LAYERS table of '
               'scripts/check_style.py (or move it into a layer)' % path)
        return
    for unit in root.children:
        for scope in walk(unit):
            for stmt in scope.statements:
                m = USE.match(stmt.code)
                if not m or m.group(1) == 'intrinsic':
                    continue
                used = m.group(2)
                other = layers.get(used)
                if other is None or other == layer or layer_rank(other) is None:
                    continue           # not a module of this package (hdf5), the same layer,
                                       # or one in an unknown folder (reported there)
                if layer_rank(other) > TIER[layer]:
                    why = 'which is above it'
                elif layer_rank(other) == TIER[layer] and (layer, other) not in SIBLING_USES:
                    why = 'a sibling layer that the LAYERS table does not let it use'
                else:
                    continue
                report(stmt.first, 'layering', '%s %s (layer %s) uses %s (layer %s), %s'
                       % (unit.kind, unit.name, layer, used, other, why))


def check_intents(proc, report):
    """Every dummy of proc has an intent, or is value or a non-pointer dummy procedure."""
    attrs = {}
    for stmt in proc.statements:
        decl = declaration(stmt.code)
        if decl:
            keyword, attributes, names = decl
            kinds = attribute_names(attributes)
            if keyword == 'procedure':
                kinds.add('procedure')
            kinds.add('declared')
            for name in names:
                attrs.setdefault(name, set()).update(kinds)
            continue
        m = ATTR_STATEMENT.match(stmt.code)
        if m:
            kind = re.match(r'^[a-z_]+', m.group(1)).group(0)
            for entity in split_top(m.group(3)):
                n = re.match(r'^([a-z_]\w*)', entity)
                if n:
                    attrs.setdefault(n.group(1), set()).add('procedure' if kind == 'external' else kind)
    for child in proc.children:       # interface bodies of dummy procedures
        if child.kind == 'interface':
            for body in child.children:
                attrs.setdefault(body.name, set()).add('procedure')
    for arg in proc.args:
        if arg == '*':
            report(proc.stmt.first, 'legacy', '%s %s: alternate return' % (proc.kind, proc.name))
            continue
        kinds = attrs.get(arg, set())
        if 'intent' in kinds or 'value' in kinds:
            continue
        if 'procedure' in kinds and 'pointer' not in kinds:
            continue
        what = 'pointer dummy' if 'pointer' in kinds else 'dummy'
        if not kinds:
            what = 'undeclared dummy'
        report(proc.stmt.first, 'intent', '%s %s: %s %s has no intent' % (proc.kind, proc.name, what, arg))


def check_module_state(module, report):
    """Every declaration in the module's specification part is a parameter."""
    for stmt in module.statements:
        if stmt.first > module.contains_at:
            continue
        decl = declaration(stmt.code)
        if decl:
            keyword, attributes, names = decl
            kinds = attribute_names(attributes)
            if 'parameter' in kinds:
                continue
            if keyword == 'procedure' and 'pointer' not in kinds:
                continue               # an external procedure's interface, not a variable
            report(stmt.first, 'global-state', 'module variable %s in %s: global mutable state%s'
                   % (', '.join(names), module.name, ' (protected)' if 'protected' in kinds else ''))
        elif re.match(r'^(save|data)\b(?!\s*=)', stmt.code):
            report(stmt.first, 'global-state', '`%s` in module %s' % (stmt.code.split()[0], module.name))


BINDING = re.compile(r'^procedure\b\s*(\(\s*([a-z_]\w*)\s*\))?\s*(.*)$')


def type_bindings(t):
    """[(binding, implementation or None if deferred, interface, attributes, statement)] of type t."""
    found = []
    for stmt in t.statements:
        m = BINDING.match(stmt.code)
        if not m or not binding_part(t, stmt):
            continue
        attrs, _, names = m.group(3).rpartition('::')
        attrs = [a.strip() for a in split_top(attrs)]
        for item in split_top(names):
            binding, _, impl = item.partition('=>')
            binding = binding.strip()
            found.append((binding, None if m.group(2) else (impl.strip() or binding), m.group(2), attrs, stmt))
    return found


def type_index(root):
    """{type name: (parent type or None, binding names)} of the types defined in a file."""
    index = {}
    for scope in walk(root):
        if scope.kind == 'type':
            parent = re.search(r'extends\(([a-z_]\w*)\)', scope.attrs)
            index[scope.name] = (parent.group(1) if parent else None,
                                 {b[0] for b in type_bindings(scope)})
    return index


def inherited(type_name, binding, index):
    """True when an ancestor of type_name (known to index) has the binding."""
    seen = set()
    parent = index.get(type_name, (None, set()))[0]
    while parent and parent not in seen and parent in index:
        seen.add(parent)
        if binding in index[parent][1]:
            return True
        parent = index[parent][0]
    return False


def check_docs(module, lines, trailing_docs, report, index):
    """Doc comments on the public procedures of a module (see RULES)."""
    public, private = set(), set()
    for stmt in module.statements:
        m = re.match(r'^(public|private)\b\s*(::)?\s*(.*)$', stmt.code)
        if m and m.group(3):
            names = {n.replace(' ', '') for n in split_top(m.group(3))}
            (public if m.group(1) == 'public' else private).update(names)

    def is_public(name):
        return name in public or (not module.default_private and name not in private)

    required = {}                      # name -> (why, binding statements documenting it too)
    for t in (c for c in module.children if c.kind == 'type'):
        attrs = t.attrs.split(',') if t.attrs else []
        if not (is_public(t.name) or 'public' in attrs) or 'private' in attrs:
            continue
        bindings_private = any(stmt.code == 'private' and binding_part(t, stmt) for stmt in t.statements)
        for binding, impl, interface, battrs, stmt in type_bindings(t):
            if 'private' in battrs or (bindings_private and 'public' not in battrs):
                continue
            if impl is None:           # deferred: the binding or its abstract interface documents it
                why = required.setdefault(interface, ['interface of deferred binding %s%%%s' % (t.name, binding)])
                why.append(stmt)
            elif not inherited(t.name, binding, index):
                why = required.setdefault(impl, ['bound to public type %s as %s' % (t.name, binding)])
                why.append(stmt)

    blocks = {}                        # procedure -> its interface block
    for child in module.children:
        if child.kind in ('subroutine', 'function') and is_public(child.name):
            required.setdefault(child.name, ['public'])
        if child.kind == 'interface':
            if child.generic and is_public(child.generic):
                if not documented(lines, child.stmt, trailing_docs):
                    report(child.stmt.first, 'doc-comment',
                           'public generic interface %s has no FORD doc comment' % child.generic)
                continue
            for body in child.children:
                blocks[body.name] = child
                if body.kind in ('subroutine', 'function') and (is_public(body.name) and not child.abstract
                                                                or body.name in public):
                    required.setdefault(body.name, ['public'])
    defined = {}
    for child in module.children:
        if child.kind in ('subroutine', 'function'):
            defined[child.name] = child
        elif child.kind == 'interface' and not child.generic:
            for body in child.children:
                defined.setdefault(body.name, body)
    for name, (why, *bindings) in sorted(required.items()):
        proc = defined.get(name)
        if not proc or documented(lines, proc.stmt, trailing_docs):
            continue
        if any(documented(lines, stmt, trailing_docs) for stmt in bindings):
            continue                   # a documented binding documents its procedure
        block = blocks.get(name)       # a doc comment before a one-procedure interface block
        if block is not None and len(block.children) == 1 and documented(lines, block.stmt, trailing_docs):
            continue
        report(proc.stmt.first, 'doc-comment', '%s %s (%s) has no FORD doc comment' % (proc.kind, name, why))


def binding_part(t, stmt):
    """True when stmt lies after the `contains` of type t (its type-bound procedure part)."""
    return stmt.first > t.contains_at


def fortran_files(paths):
    if paths:
        return sorted(paths)
    found = []
    for top in DIRS:
        for directory, subdirs, files in os.walk(os.path.join(ROOT, top)):
            subdirs.sort()
            found.extend(os.path.relpath(os.path.join(directory, f), ROOT)
                         for f in files if f.endswith(SUFFIXES))
    return sorted(found)


def check_files(paths):
    files = fortran_files(paths)
    sources, index, layers = {}, {}, {}
    for path in files:
        full = path if os.path.isabs(path) else os.path.join(ROOT, path)
        with open(full, encoding='utf-8') as f:
            sources[os.path.relpath(full, ROOT)] = f.read()
    for path in fortran_files([]) if paths else []:   # the ancestors of a checked file's types,
        if path not in sources:                       # the layers of the modules it uses
            with open(os.path.join(ROOT, path), encoding='utf-8') as f:
                root = parse(f.read())[0]
            index.update(type_index(root))
            layers.update(module_layers(path, root))
    for rel, text in sources.items():
        root = parse(text)[0]
        index.update(type_index(root))
        layers.update(module_layers(rel, root))
    count = 0
    for rel, text in sources.items():
        for line, rule, message in check_source(rel, text, index, layers):
            print('%s:%d: %s: %s' % (rel, line, rule, message))
            count += 1
    if count:
        print('check_style: %d violation%s in %d files' % (count, '' if count == 1 else 's', len(files)))
        return 1
    print('check_style: %d files, no violation' % len(files))
    return 0


GOOD = '''\
!> A module that follows every rule.
module good_mod
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int
  implicit none
  private

  public :: area, scale_t, shape_t, norm, c_free ; public :: apply

  integer, parameter, public :: n_max = 10   !! a constant is no state
  character(len=*), parameter :: bang = 'it''s not a comment! print *, "x"'

  !> A shape.
  type, abstract :: shape_t
  contains
    procedure(area_interface), deferred :: area_of
    procedure :: describe => shape_describe
    procedure :: perimeter => shape_perimeter   !! its perimeter
    procedure, private :: helper
  end type shape_t

  type :: scale_t
    real :: factor = 1.0
  end type scale_t

  !> A square: its bindings override documented ones and need no comment of their own.
  type, extends(shape_t), public :: square_t
  contains
    procedure :: area_of => square_area
    procedure :: describe => square_describe
  end type square_t

  abstract interface
    !> Area of a shape.
    pure real function area_interface(self)
      import :: shape_t
      class(shape_t), intent(in) :: self
    end function area_interface
  end interface

  !> Euclidean norm.
  interface norm
    module procedure norm_real
  end interface norm

  interface
    !> Free a C handle.
    subroutine c_free(handle) bind(C, name="free")
      import :: c_ptr
      type(c_ptr), value :: handle
    end subroutine c_free
  end interface

contains

  !> Area of a rectangle, written in a
  !! long way.
  pure real function area(width, &
      height) result(a)
    real, intent(in) :: width, &
      height
    a = width * height ; if (a < 0) a = 0
  end function area

  subroutine shape_describe(self, text)
    !! What the shape is.
    class(shape_t), intent(in) :: self
    character(len=:), allocatable, intent(out) :: text
    text = 'a shape; stop print'
  end subroutine shape_describe

  pure real function shape_perimeter(self)
    class(shape_t), intent(in) :: self
    shape_perimeter = 0
  end function shape_perimeter

  subroutine helper(self)
    class(shape_t), intent(in) :: self
  end subroutine helper

  pure real function square_area(self)
    class(square_t), intent(in) :: self
    square_area = 1
  end function square_area

  subroutine square_describe(self, text)
    class(square_t), intent(in) :: self
    character(len=:), allocatable, intent(out) :: text
    text = 'a square'
  end subroutine square_describe

  pure real function norm_real(x)
    real, intent(in) :: x(:)
    norm_real = sqrt(sum(x**2))
  end function norm_real

  !> Apply f to x.
  subroutine apply(f, x, unit)
    interface
      subroutine f(y)
        real, intent(inout) :: y
      end subroutine f
    end interface
    real, intent(inout) :: x
    integer, intent(in) :: unit
    call f(x)
    write (unit, '(a)') 'done'
  end subroutine apply
end module good_mod
'''

# (rule, path, source): each must be reported under rule.
BAD = [
    ('one-module', 'src/bad/two_mods.f90',
     'module two_mods\n  implicit none\n  private\nend module two_mods\n'
     'module other\n  implicit none\n  private\nend module other\n'),
    ('one-module', 'src/bad/wrong_name.f90', 'module right_name\n  implicit none\n  private\nend module\n'),
    ('implicit-none', 'src/bad/no_implicit.f90', 'module no_implicit\n  private\nend module no_implicit\n'),
    ('implicit-none', 'app/prog.f90', 'program prog\n  print *, 1\nend program prog\n'),
    ('private-default', 'src/bad/no_private.f90',
     'module no_private\n  implicit none\n  public :: f\ncontains\n  !> F.\n  subroutine f()\n  end subroutine f\n'
     'end module no_private\n'),
    ('intent', 'src/bad/no_intent.f90',
     'module no_intent\n  implicit none\n  private\n  public :: f\ncontains\n  !> F.\n'
     '  subroutine f(a, &\n      b)\n    real, intent(in) :: a\n    real :: b\n  end subroutine\nend module\n'),
    ('intent', 'src/bad/abstract_intent.f90',
     'module abstract_intent\n  implicit none\n  private\n  abstract interface\n'
     '    function g(x) result(y)\n      real :: x\n      real :: y\n    end function g\n'
     '  end interface\nend module abstract_intent\n'),
    ('intent', 'test/pointer_intent.f90',
     'module pointer_intent\n  implicit none\n  private\ncontains\n'
     '  subroutine h(p)\n    real, pointer :: p(:)\n  end subroutine h\nend module pointer_intent\n'),
    ('no-stop-print', 'src/bad/stops.f90',
     'module stops\n  implicit none\n  private\ncontains\n  subroutine s(x)\n    real, intent(in) :: x\n'
     '    if (x < 0) error stop "negative"\n  end subroutine s\nend module stops\n'),
    ('no-stop-print', 'src/bad/prints.f90',
     'module prints\n  implicit none\n  private\ncontains\n  subroutine s()\n    PRINT *, "x"\n'
     '  end subroutine s\nend module prints\n'),
    ('no-stop-print', 'src/bad/writes.f90',
     'module writes\n  use iso_fortran_env, only: error_unit\n  implicit none\n  private\ncontains\n'
     '  subroutine s()\n    write (error_unit, *) "x"\n  end subroutine s\nend module writes\n'),
    ('legacy', 'test/bad_common.f90',
     'module bad_common\n  implicit none\n  private\n  common /blk/ a\nend module bad_common\n'),
    ('legacy', 'test/bad_goto.f90',
     'module bad_goto\n  implicit none\n  private\ncontains\n  subroutine s(i)\n    integer, intent(in) :: i\n'
     '    if (i > 0) go to 10\n10  continue\n  end subroutine s\nend module bad_goto\n'),
    ('legacy', 'test/bad_implicit.f90',
     'module bad_implicit\n  implicit double precision (a-h, o-z)\n  private\nend module bad_implicit\n'),
    ('legacy', 'test/bad_equiv.f90',
     'module bad_equiv\n  implicit none\n  private\n  real :: a, b\n  equivalence (a, b)\nend module bad_equiv\n'),
    ('legacy', 'test/bad_include.f90',
     'module bad_include\n  implicit none\n  private\n  include "other.f90"\nend module bad_include\n'),
    ('doc-comment', 'src/bad/undocumented.f90',
     'module undocumented\n  implicit none\n  private\n  public :: f\ncontains\n\n'
     '  ! an ordinary comment is no doc comment\n  subroutine f()\n  end subroutine f\nend module undocumented\n'),
    ('doc-comment', 'src/bad/bound.f90',
     'module bound\n  implicit none\n  private\n  !> T.\n  type, public :: t\n  contains\n'
     '    procedure :: go => t_go\n  end type t\ncontains\n  subroutine t_go(self)\n'
     '    class(t), intent(in) :: self\n  end subroutine t_go\nend module bound\n'),
    ('doc-comment', 'app/two_docs.f90',
     'program two_docs\n  implicit none\ncontains\n  !> Orphaned doc of a procedure moved away.\n'
     '  !> Area.\n  real function area()\n    area = 1\n  end function area\nend program two_docs\n'),
    ('global-state', 'src/bad/state.f90',
     'module state\n  implicit none\n  private\n  integer, save :: calls = 0\nend module state\n'),
    ('global-state', 'src/bad/protect.f90',
     'module protect\n  implicit none\n  private\n  real, protected, public :: tol\nend module protect\n'),
    ('layering', 'src/core/uses_high.f90',     # a core module that uses an output one
     'module uses_high\n  use high_mod, only: h\n  implicit none\n  private\nend module uses_high\n'),
    ('layering', 'src/assembly/uses_sibling.f90',   # assembly uses solvers, in a procedure
     'module uses_sibling\n  implicit none\n  private\ncontains\n  subroutine s()\n'
     '    use, non_intrinsic :: solver_mod\n  end subroutine s\nend module uses_sibling\n'),
    ('layering', 'src/nowhere/lost.f90',       # a folder that the LAYERS table does not name
     'module lost\n  implicit none\n  private\nend module lost\n'),
]

# The modules that the layering snippets use, each in the layer of its folder.
LAYER_MODULES = {
    'src/core/low_mod.f90': 'module low_mod\n  implicit none\n  private\nend module low_mod\n',
    'src/assembly/asm_mod.f90': 'module asm_mod\n  implicit none\n  private\nend module asm_mod\n',
    'src/solvers/solver_mod.f90': 'module solver_mod\n  implicit none\n  private\nend module solver_mod\n',
    'src/output/high_mod.f90': 'module high_mod\n  implicit none\n  private\nend module high_mod\n',
}

# (path, source): allowed uses, of which none may be reported: a lower layer, the same layer,
# intrinsic and outside modules; test/ and app/ using the highest layers.
LAYER_GOOD = [
    ('src/assembly/uses_lower.f90',
     'module uses_lower\n  use, intrinsic :: iso_fortran_env, only: int64\n  use hdf5, only: hid_t\n'
     '  use low_mod\n  use :: asm_mod\n  implicit none\n  private\nend module uses_lower\n'),
    ('test/test_high.f90',
     'module test_high\n  use high_mod\n  use solver_mod\n  implicit none\n  private\nend module test_high\n'),
    ('app/main_high.f90', 'program main_high\n  use high_mod\n  implicit none\nend program main_high\n'),
]


def self_test():
    failures = 0
    layers = {}
    for path, source in LAYER_MODULES.items():
        layers.update(module_layers(path, parse(source)[0]))
    good = check_source('src/core/good_mod.f90', GOOD, layers=layers)
    if good:
        failures += 1
        print('self-test FAIL: the good module reports %s' % good)
    for path, source in LAYER_GOOD:
        good = check_source(path, source, layers=layers)
        if good:
            failures += 1
            print('self-test FAIL: the allowed uses of %s report %s' % (path, good))
    for rule, path, source in BAD:
        got = check_source(path, source, layers=layers)
        if not any(r == rule for _, r, _ in got):
            failures += 1
            print('self-test FAIL: %s not reported for %s: %s' % (rule, path, got))
    # Without its doc comments, the good module's 7 public procedures are reported.
    undocumented = check_source('src/core/good_mod.f90', re.sub(r'!(!|>)', '! ', GOOD), layers=layers)
    if [r for _, r, _ in undocumented] != ['doc-comment'] * 7:
        failures += 1
        print('self-test FAIL: the good module without doc comments reports %s' % undocumented)
    missing = set(RULE_NAMES) - {rule for rule, _, _ in BAD}
    if missing:
        failures += 1
        print('self-test FAIL: no bad snippet for %s' % ', '.join(sorted(missing)))
    if failures:
        print('check_style self-test: %d failure%s' % (failures, '' if failures == 1 else 's'))
        return 1
    print('check_style self-test: %d bad snippets caught, the good module and %d allowed uses pass'
          % (len(BAD), len(LAYER_GOOD)))
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('files', nargs='*', help='files to check (default: every Fortran file under src, app, test)')
    parser.add_argument('--list-rules', action='store_true', help='list the rules and exit')
    parser.add_argument('--self-test', action='store_true', help='check that every rule catches a bad snippet')
    args = parser.parse_args()
    if args.list_rules:
        for name, text in RULES:
            print('%-16s %s' % (name, text))
        return 0
    if args.self_test:
        return self_test()
    return check_files(args.files)


if __name__ == '__main__':
    sys.exit(main())
