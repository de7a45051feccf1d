#!/usr/bin/env python3
"""Translate the subset of pFUnit .pf syntax that spallbar uses into plain Fortran.

Used when the build is configured without real pFUnit (SPALLBAR_TEST_FRAMEWORK=translator,
or no pFUnit found). The same .pf files compile under real pFUnit 4.14 (see doc/build.md,
"What pFUnit 4.14 requires of a .pf file"); this translator gives the same verdicts:

  * @test, @before, @after, @disable annotate the next `subroutine NAME`;
  * @assertXxx(args) becomes `call assertXxx(args, location='file:line')` followed by
    `if (anyExceptions()) return` (a test stops at its first failing assertion);
  * `use funit` resolves to tests/funit.f90, the fallback implementation.

It refuses (exit 1, `pf2f90: FILE:LINE: ...`) every directive that pFUnit 4.14 cannot take:
a directive whose pFUnit translation `  call assertXxx(ARGS, &` is longer than 132 columns
(funitproc copies the arguments onto one line, and gfortran stops at "Line truncated"), a
directive continued with `&` or followed by a comment, an assertion with fewer arguments
than pFUnit's parser requires (it leaves such a line untranslated), arguments on @test,
@before, @after or @disable, and any directive outside the subset below.

Usage:
  pf2f90.py FILE.pf --list                 print the test names, one per line
  pf2f90.py FILE.pf --out-dir DIR          write DIR/NAME.f90 and DIR/NAME_driver.f90
"""
import os
import re
import sys

ASSERTS = {
    "assertequal": "assertEqual",
    "assertnotequal": "assertNotEqual",
    "assertrelativelyequal": "assertRelativelyEqual",
    "asserttrue": "assertTrue",
    "assertfalse": "assertFalse",
    "assertlessthan": "assertLessThan",
    "assertlessthanorequal": "assertLessThanOrEqual",
    "assertgreaterthan": "assertGreaterThan",
    "assertgreaterthanorequal": "assertGreaterThanOrEqual",
    "assertisfinite": "assertIsFinite",
    "assertisnan": "assertIsNaN",
    "assertfail": "assertFail",
}
# pFUnit 4.14 (bin/funit/pFUnitParser.py, assert_operands): an @assert line with fewer
# comma-separated operands than this is not recognised and stays in the source untranslated.
MIN_OPERANDS = {
    "assertequal": 2, "assertnotequal": 2, "assertrelativelyequal": 2, "asserttrue": 1,
    "assertfalse": 1, "assertlessthan": 2, "assertlessthanorequal": 2,
    "assertgreaterthan": 2, "assertgreaterthanorequal": 2, "assertisfinite": 1,
    "assertisnan": 1, "assertfail": 0,
}
FORTRAN_LINE_LIMIT = 132  # gfortran free form; pFUnit's build treats truncation as an error
DIRECTIVE = re.compile(r"^(\s*)@(\w+)\s*(\((.*)\))?\s*$")
SUBROUTINE = re.compile(r"^\s*subroutine\s+(\w+)", re.IGNORECASE)
MODULE = re.compile(r"^\s*module\s+(\w+)\s*$", re.IGNORECASE)


class PfError(Exception):
    pass


def split_args(args):
    """Split an argument list at its top-level commas (not inside () or strings)."""
    parts, depth, quote, cur = [], 0, None, []
    for ch in args:
        if quote:
            cur.append(ch)
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
            cur.append(ch)
        elif ch in "([":
            depth += 1
            cur.append(ch)
        elif ch in ")]":
            depth -= 1
            cur.append(ch)
        elif ch == "," and depth == 0:
            parts.append("".join(cur).strip())
            cur = []
        else:
            cur.append(ch)
    if "".join(cur).strip():
        parts.append("".join(cur).strip())
    return parts


def pfunit_line(variant, args):
    """The line funitproc 4.14 writes for `@assert<variant>(<args>)` (AtAssert.action)."""
    line = "  call assert" + variant + "(" + args
    if args and not args.isspace():
        line += ", "
    return line + "&"


def check_assert(path, lineno, written, name, args):
    """Refuse what pFUnit cannot take; `written` is the directive's name as in the file."""
    operands = args.count(",") + (1 if args and not args.isspace() else 0)
    if operands < MIN_OPERANDS[name]:
        raise PfError(f"{path}:{lineno}: @{written} needs at least {MIN_OPERANDS[name]} "
                      "argument(s); pFUnit would leave the line untranslated")
    width = len(pfunit_line(written[len("assert"):], args))
    if width > FORTRAN_LINE_LIMIT:
        raise PfError(f"{path}:{lineno}: @{written} becomes a {width}-column line under "
                      f"pFUnit (limit {FORTRAN_LINE_LIMIT}: funitproc puts all arguments on "
                      "one line); shorten it, e.g. with a local variable")


def translate(path):
    base = os.path.splitext(os.path.basename(path))[0]
    out, tests, before, after = [], [], None, None
    pending = None  # 'test' | 'before' | 'after' | 'disabled'
    module = None
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    for lineno, line in enumerate(lines, start=1):
        m = DIRECTIVE.match(line)
        if m:
            indent, name, _, args = m.group(1), m.group(2).lower(), m.group(3), m.group(4)
            if name in ("test", "before", "after", "disable") and m.group(3) is not None:
                raise PfError(f"{path}:{lineno}: @{m.group(2)} takes no arguments here")
            if name == "test":
                pending = "disabled" if pending == "disabled" else "test"
            elif name in ("before", "after", "disable"):
                pending = {"disable": "disabled"}.get(name, name)
            elif name in ASSERTS:
                if args is None:
                    raise PfError(f"{path}:{lineno}: @{m.group(2)} needs (arguments)")
                check_assert(path, lineno, m.group(2), name, args)
                parts = split_args(args) + [f"location='{base}.pf:{lineno}'"]
                # one argument per continuation line keeps every line within 132 columns
                body = (", &\n" + indent + "   ").join(parts)
                out.append(f"{indent}call {ASSERTS[name]}( &\n{indent}   {body})")
                out.append(f"{indent}if (anyExceptions()) return")
            else:
                raise PfError(f"{path}:{lineno}: directive @{m.group(2)} is not supported here")
            if name not in ASSERTS:
                out.append("")  # keep line numbers roughly aligned
            continue
        if line.lstrip().startswith("@"):
            raise PfError(f"{path}:{lineno}: a directive must stand alone on its line "
                          "with nothing after its closing ')'")
        mm = MODULE.match(line)
        if mm and module is None:
            module = mm.group(1)
            if module.lower() != base.lower():
                raise PfError(f"{path}: module '{module}' must be named like the file ('{base}')")
        ms = SUBROUTINE.match(line)
        if ms and pending:
            sub = ms.group(1)
            if pending == "test":
                tests.append(sub)
            elif pending == "before":
                before = sub
            elif pending == "after":
                after = sub
            pending = None
        out.append(line)
    if module is None:
        raise PfError(f"{path}: no module found")
    return base, "\n".join(out) + "\n", tests, before, after


def driver(base, tests, before, after):
    calls = []
    for t in tests:
        calls.append(f"   if (wanted('{t}')) then")
        calls.append(f"      call start_test('{t}')")
        if before:
            calls.append(f"      call {before}()")
        calls.append(f"      if (.not. anyExceptions()) call {t}()")
        if after:
            calls.append(f"      call {after}()")
        calls.append("      call end_test()")
        calls.append("   end if")
    body = "\n".join(calls)
    return f"""! generated by pf2f90.py from {base}.pf -- do not edit
program {base}_driver
   use funit, only: anyExceptions, start_test, end_test, finish_run
   use {base}
   implicit none
   character(len=256) :: only
   integer :: nargs
   nargs = command_argument_count()
   only = ''
   if (nargs >= 1) call get_command_argument(1, only)
{body}
   call finish_run(trim(only))
contains
   logical function wanted(name)
      character(len=*), intent(in) :: name
      wanted = len_trim(only) == 0 .or. trim(only) == name
   end function wanted
end program {base}_driver
"""


def main(argv):
    if len(argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    path = argv[1]
    try:
        base, text, tests, before, after = translate(path)
    except PfError as e:
        print(f"pf2f90: {e}", file=sys.stderr)
        return 1
    if argv[2] == "--list":
        print("\n".join(tests))
        return 0
    if argv[2] == "--out-dir" and len(argv) == 4:
        os.makedirs(argv[3], exist_ok=True)
        for name, content in ((f"{base}.f90", text),
                              (f"{base}_driver.f90", driver(base, tests, before, after))):
            target = os.path.join(argv[3], name)
            old = open(target).read() if os.path.exists(target) else None
            if old != content:
                with open(target, "w") as f:
                    f.write(content)
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
