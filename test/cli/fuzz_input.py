#!/usr/bin/env python3
"""Fuzz feps's input handling: mutate valid decks at random and require a clear answer.

    python3 test/cli/fuzz_input.py [--feps PATH] [--decks GLOB ...] [--cases N] [--seed S]
                                  [--run] [--hostile] [--timeout S] [--memory-gb G] [--out DIR]

Each case takes a deck (default: the small decks in test/data), changes one to three of its
lines (a field replaced by junk or an extreme number, a line deleted, duplicated or cut short,
the file cut off) and runs `feps --check` on it, or the whole analysis with `--run`. The
mutant sits in a copy of the deck's folder, so INCLUDE still finds its files.

A case passes when feps ends with
  - exit 0 (the mutant is still a valid deck), or
  - exit 2 and exactly one line on stderr, `feps: error: ...` naming the mutant's file
    (bad input; `feps: warning: ...` lines before it, such as a unit-slip warning about a
    mutated modulus, are not counted), or
  - with `--run` only: exit 1 and exactly one `feps: error: ...` line (a clear numerical stop,
    such as a step that does not converge after its cut-backs),
and, when it did not end with 0, left no result file. Anything else fails: another exit
status (a crash, a Fortran runtime error), more than one line, a message without the file, a
run past `--timeout` (a hang; with `--run`, a run still writing progress lines gets up to three
times --timeout, as long as it writes one at least every 15 s, and a run still stepping through
a mutated STEPS= of 100 000 or more is reported as a long run instead), or memory past `--memory-gb` (the limit turns a runaway
allocation into a failure instead of taking the machine). Failing mutants are copied to
`--out` (default results/fuzz) with the command that failed. Exit status 1 if any case failed.

With --hostile (issue 24) a case may also get what a hostile user or a failing machine brings:
integers at and beyond the 32-bit range (-2147483648), subnormal numbers, a control byte or a
byte that is not UTF-8 (in a name), a line of 200 000 characters, an `INCLUDE` of /dev/zero, of a
FIFO or of a directory; and one machine fault: the results file's size limited (ulimit -f, as a
full disk), the address space cut to 0.5 to 1.5 GB (ulimit -v), or the results name an existing
directory holding a file, which must be refused (exit 2) and kept. A case with a machine fault
may end with exit 1 and one line also under --check. Every case must leave no .h5, .h5.part,
.xmf or .xmf.part unless it ends with exit 0.

The same seed gives the same cases. check_cli.sh runs a short fixed-seed campaign (with
--hostile too); longer ones (docs/verification.md, "Input fuzzing") are run by hand, e.g.
`python3 test/cli/fuzz_input.py --feps build/.../feps --hostile --run --cases 2000 --seed 24`.
"""
import argparse
import glob
import os
import random
import re
import resource
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from feps_cli import feps_executable  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

JUNK = ['', 'abc', '-1', '0', '1e400', 'nan', 'inf', '-inf', '1e-400', '999999999999',
        '2147483648', '-0', '1.5', ',', '=', "'", '1d5', '*', '  ', 'E=', ',,,', '1e308',
        '-1e308', '100000000']
EXTREME_NUMBERS = ['0', '-1', '1e30', '1e-30', '0.5', '-0.999', '100000000', '3', '0.4999999']
# --hostile: beyond the 32-bit range, subnormal, control bytes and bytes that are not UTF-8 (the
# mutant is written as Latin-1: '\xe9' becomes the single byte 0xe9), a line beyond the limit
HOSTILE_JUNK = ['-2147483648', '2147483647', '-2147483647', '9223372036854775808', '1e-320', '4.9e-324',
                'a\x1bb', 'caf\xe9', '\x00', 'x' * 200000]
HOSTILE_INCLUDES = ['/dev/zero', '{fifo}', '{dir}', '/dev/null']
NUMBER = re.compile(r'-?\d+(\.\d*)?([eEdD][-+]?\d+)?')
SPLIT = re.compile(r'(\s*[,=]\s*|\s+)')


def mutate(text, rng, hostile=False, specials=None):
    """One to three random changes to the deck's lines; the file may also be cut off. With
    `hostile`, also the junk of HOSTILE_JUNK and INCLUDE records of `specials` (fifo, dir)."""
    lines = text.split('\n')
    for _ in range(rng.randint(1, 3)):
        if not lines:
            break
        i = rng.randrange(len(lines))
        tokens = SPLIT.split(lines[i])
        op = rng.randrange(8 if hostile else 6)
        if op >= 6:
            if op == 6:
                tokens[rng.randrange(len(tokens))] = rng.choice(HOSTILE_JUNK)
                lines[i] = ''.join(tokens)
            else:
                lines.insert(i, 'INCLUDE, ' + rng.choice(HOSTILE_INCLUDES).format(**(specials or {})))
        elif op == 0:
            tokens[rng.randrange(len(tokens))] = rng.choice(JUNK)
            lines[i] = ''.join(tokens)
        elif op == 1:
            del lines[i]
        elif op == 2:
            lines.insert(i, lines[rng.randrange(len(lines))])
        elif op == 3:
            lines[i] = lines[i][:rng.randrange(len(lines[i]) + 1)]
        elif op == 4:
            numbers = [k for k, t in enumerate(tokens) if NUMBER.fullmatch(t.strip())]
            if numbers:
                tokens[rng.choice(numbers)] = rng.choice(EXTREME_NUMBERS)
                lines[i] = ''.join(tokens)
        else:
            lines = lines[:i]
            break
    return '\n'.join(lines)


def limit_memory(gigabytes, file_kb=None):
    def apply():
        limit = int(gigabytes * 2**30)
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))
        if file_kb is not None:
            resource.setrlimit(resource.RLIMIT_FSIZE, (file_kb * 1024, file_kb * 1024))
    return apply


# A run past --timeout that is still writing progress lines (steps, cut-backs) is slow, not hung:
# it gets up to SLOW_FACTOR x --timeout in all, as long as its progress grows at least every
# QUIET seconds. (A mutated mesh can make a plastic run cut back at every step: one such mutant
# takes 66 s in the debug build to reach its clear "does not converge" stop.)
SLOW_FACTOR = 3.0
QUIET = 15.0


def run_with_progress(command, cwd, stdout, progress, timeout, running, memory_gb, file_kb=None):
    """(exit status, stderr) of feps; subprocess.TimeoutExpired (the process killed) when it runs
    past `timeout` without progress for QUIET s (only analyses, `running`, write progress), or
    past SLOW_FACTOR x `timeout`. stderr goes to a file beside the progress file (a pipe could
    fill while nobody reads it)."""
    errors = progress + '.err'
    with open(errors, 'w') as stderr:
        proc = subprocess.Popen(command, cwd=cwd, stdout=stdout, stderr=stderr, preexec_fn=limit_memory(memory_gb, file_kb))
        waited, size = 0.0, -1
        limit = timeout
        while True:
            try:
                proc.wait(timeout=limit - waited)
                break
            except subprocess.TimeoutExpired:
                waited = limit
                grown = os.path.getsize(progress)
                if not running or grown == size or waited >= SLOW_FACTOR * timeout:
                    proc.kill()
                    proc.wait()
                    raise
                size = grown
                limit = waited + QUIET
    with open(errors, errors='replace') as f:   # a message may quote a byte that is not UTF-8
        return proc.returncode, f.read()


def long_run(progress):
    """The steps a stage asks for, if the progress file shows a run still stepping through a
    stage of at least 100 000 steps (a mutated STEPS=; a long run, not a hang), else 0."""
    try:
        with open(progress, 'rb') as f:
            f.seek(0, os.SEEK_END)
            f.seek(max(0, f.tell() - 4096))
            tail = f.read().decode(errors='replace').splitlines()
    except OSError:
        return 0
    steps = [re.search(r'step\s+(\d+)/(\d+)', line) for line in tail]
    steps = [(int(m.group(1)), int(m.group(2))) for m in steps if m]
    if len(steps) >= 2 and steps[-1][1] >= 100000 and steps[-1][0] > steps[0][0]:
        return steps[-1][1]
    return 0


def judge(status, stderr, mutant, run_mode, leftovers, fault=None):
    """None if feps answered clearly, else what was wrong."""
    # a warning (a value far outside N-mm-MPa) comes before the error it may explain
    lines = [line for line in stderr.splitlines() if line.strip() and not line.startswith('feps: warning: ')]
    if fault == 'outdir' and status == 0 and run_mode:   # --check writes nothing and checks no path
        return 'exit 0 with an existing directory as the results file'
    if status == 0:
        return None
    if leftovers:
        return f'exit {status} but left {", ".join(leftovers)}'
    if status not in (1, 2) or (status == 1 and not run_mode and fault is None):
        return f'exit {status}'
    if len(lines) != 1:
        return f'exit {status} with {len(lines)} lines on stderr'
    if not lines[0].startswith('feps: error: '):
        return f'exit {status}: the line is not "feps: error: ..."'
    if status == 2 and fault != 'outdir' and os.path.basename(mutant) not in lines[0]:
        return 'exit 2: the message does not name the file'
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--feps', help='the feps executable (default: the debug build, via fpm)')
    ap.add_argument('--decks', nargs='+', default=[os.path.join(ROOT, 'test', 'data', '*.dat')],
                    help='glob patterns of the decks to mutate (default: test/data/*.dat)')
    ap.add_argument('--max-size', type=int, default=6000,
                    help='leave out decks larger than this many bytes (default 6000)')
    ap.add_argument('--cases', type=int, default=100)
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--run', action='store_true', help='run the analyses, not only --check')
    ap.add_argument('--hostile', action='store_true',
                    help='also hostile junk (integer limits, control bytes, long lines, INCLUDE of devices) '
                         'and machine faults (file-size and address-space limits, a directory as the results)')
    ap.add_argument('--timeout', type=float, default=60.0, help='seconds per case (default 60)')
    ap.add_argument('--memory-gb', type=float, default=4.0, help='address space per case (default 4)')
    ap.add_argument('--out', default=os.path.join(ROOT, 'results', 'fuzz'))
    args = ap.parse_args()
    if args.cases < 1:
        sys.exit('fuzz_input.py: --cases must be at least 1')

    feps = args.feps or feps_executable('debug')
    feps = os.path.abspath(feps)
    if not os.access(feps, os.X_OK):
        sys.exit(f'fuzz_input.py: cannot run feps at {feps!r} (--feps)')

    decks = sorted({d for pattern in args.decks for d in glob.glob(pattern)
                    if os.path.getsize(d) <= args.max_size})
    if not decks:
        sys.exit('fuzz_input.py: no deck matches --decks within --max-size')

    rng = random.Random(args.seed)
    failures = []
    outcomes = {}
    with tempfile.TemporaryDirectory(prefix='feps_fuzz_') as work:
        specials = {'fifo': os.path.join(work, 'fifo.datain'), 'dir': work}
        if args.hostile:
            os.mkfifo(specials['fifo'])
        copies = {}  # a copy of each deck's folder, so INCLUDE finds its files
        for case in range(args.cases):
            deck = rng.choice(decks)
            folder = os.path.dirname(os.path.abspath(deck))
            if folder not in copies:
                copies[folder] = os.path.join(work, f'dir{len(copies)}')
                shutil.copytree(folder, copies[folder], ignore=shutil.ignore_patterns('*.h5', '*.xmf'))
            with open(deck) as f:
                text = mutate(f.read(), rng, args.hostile, specials)
            mutant = os.path.join(copies[folder], f'fuzz_{args.seed}_{case}.dat')
            with open(mutant, 'w', encoding='latin-1') as f:
                f.write(text)
            result = os.path.join(work, f'fuzz_{args.seed}_{case}.h5')
            # --hostile: one machine fault in a case of three
            fault, file_kb, memory_gb = None, None, args.memory_gb
            if args.hostile and rng.random() < 1 / 3:
                fault = rng.choice(['fsize', 'memory', 'outdir'])
                if fault == 'fsize':
                    file_kb = rng.choice([1, 8, 64, 512])
                elif fault == 'memory':
                    memory_gb = rng.choice([0.5, 1.0, 1.5])
                else:
                    result = os.path.join(work, f'outdir_{case}')
                    os.makedirs(result)
                    with open(os.path.join(result, 'keep'), 'w') as f:
                        f.write('keep\n')
            # --run keeps the progress lines (in a file: a long run writes many) to tell a
            # long run the mutant asks for from a hang
            command = [feps, mutant, '--output', result] + (['--check', '--quiet'] if not args.run else [])
            progress = os.path.join(work, 'progress.txt')
            try:
                with open(progress, 'w') as stdout:
                    returncode, stderr = run_with_progress(command, copies[folder], stdout, progress,
                                                           args.timeout, args.run, memory_gb, file_kb)
                stem = os.path.splitext(result)[0] if fault != 'outdir' else result + '_none'
                leftovers = [p for p in (result, result + '.part', stem + '.xmf', stem + '.xmf.part')
                             if os.path.isfile(p) or (p != result and os.path.exists(p))]
                problem = judge(returncode, stderr, mutant, args.run, leftovers if returncode != 0 else [], fault)
                if fault == 'outdir' and not os.path.isfile(os.path.join(result, 'keep')):
                    problem = 'the directory given as the results file (and its file) is gone'
                if fault:
                    outcomes[f'fault {fault}'] = outcomes.get(f'fault {fault}', 0) + 1
                outcomes[returncode] = outcomes.get(returncode, 0) + 1
                message = stderr.strip().replace('\n', ' | ')[:300]
            except subprocess.TimeoutExpired:
                steps = long_run(progress)
                if steps:
                    problem, message = None, ''
                    outcomes['long run'] = outcomes.get('long run', 0) + 1
                    print(f'long run (not a failure): {os.path.relpath(deck, ROOT)} mutated to {steps} steps, '
                          f'still stepping after {args.timeout:g} s')
                else:
                    problem, message = (f'no answer within {args.timeout:g} s' + (
                        f', then no new progress line for {QUIET:g} s (or still running at '
                        f'{SLOW_FACTOR * args.timeout:g} s)' if args.run else ''), '')
                    outcomes['timeout'] = outcomes.get('timeout', 0) + 1
            if fault == 'outdir':
                shutil.rmtree(result, ignore_errors=True)
            for p in (result, result + '.part', os.path.splitext(result)[0] + '.xmf',
                      os.path.splitext(result)[0] + '.xmf.part'):
                if os.path.isfile(p):
                    os.remove(p)
            if problem:
                os.makedirs(args.out, exist_ok=True)
                kept = os.path.join(args.out, os.path.basename(mutant))
                shutil.copy(mutant, kept)
                failures.append(kept)
                print(f'FAIL {kept} (from {os.path.relpath(deck, ROOT)}){" with fault " + fault if fault else ""}: '
                      f'{problem}: {message}')
                print(f'     command: {" ".join(command)} (in {os.path.dirname(deck)})')
            os.remove(mutant)

    summary = ', '.join(f'{k if str(k).startswith("fault") else f"exit {k}"}: {v}'
                        for k, v in sorted(outcomes.items(), key=str))
    print(f'fuzz_input.py: {args.cases} mutants of {len(decks)} decks (seed {args.seed}, '
          f'{"--run" if args.run else "--check"}{", --hostile" if args.hostile else ""}): {len(failures)} failed; '
          f'{summary}')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
