#!/usr/bin/env python3
# The memory over time on ingested captures (docs/history.md, "Measured"): for each seed, the
# synthetic room and the same room after `smql synth --changes` (the same walk twice) are ingested,
# the second with --update; SHOW CHANGES is compared with the changes the captures could see.
#
#   scripts/history_eval.py [--smql build/shell/smql] [--frames 30] SEED...
import argparse, json, math, os, shutil, subprocess, tempfile

parser = argparse.ArgumentParser()
parser.add_argument('--smql', default='build/shell/smql')
parser.add_argument('--frames', type=int, default=30)
parser.add_argument('seeds', type=int, nargs='+')
args = parser.parse_args()
S = os.path.abspath(args.smql)
work = tempfile.mkdtemp(prefix='smql-history-')
def run(*a):
    return subprocess.run([S, *a], capture_output=True, text=True, check=True).stdout
def vis(cap):
    d = json.loads(open(f'{cap}/visibility.json').read())
    return {x['id']: x['frames'] for x in d['instances']}
def dist(a, b): return math.dist(a, b)
tp = fp = fn = 0
for seed in args.seeds:
    w = os.path.join(work, str(seed))
    run('synth', '--out', f'{w}/a', '--seed', str(seed), '--frames', str(args.frames))
    run('synth', '--out', f'{w}/b', '--seed', str(seed), '--frames', str(args.frames), '--changes')
    run('ingest', f'{w}/a', '--db', f'{w}/db', '--scene', 'room')
    run('ingest', f'{w}/b', '--db', f'{w}/db', '--update', 'room')
    rows = json.loads(run(f'{w}/db', '-json', '-c', 'SHOW CHANGES'))
    rows = rows[0]['rows'] if isinstance(rows, list) and rows and 'rows' in rows[0] else rows
    va, vb = vis(f'{w}/a'), vis(f'{w}/b')
    truth = json.loads(open(f'{w}/b/changes.json').read())['changes']
    expected = []
    for c in truth:
        seen_a = va.get(c.get('before_id'), 0) > 0
        seen_b = vb.get(c.get('after_id'), 0) > 0
        if c['change'] == 'moved':
            if seen_a and seen_b: expected.append(('moved', c['category'], c['to']))
            elif seen_b: expected.append(('added', c['category'], c['to']))
            elif seen_a: expected.append(('missing', c['category'], c['from']))
        elif c['change'] == 'missing' and seen_a: expected.append(('missing', c['category'], c['from']))
        elif c['change'] == 'added' and seen_b: expected.append(('added', c['category'], c['to']))
    got = []
    for r in rows:
        box = r['to'] if r['change'] != 'missing' else r['from']
        got.append((r['change'], r['category'], box['center']))
    used = set(); t = 0
    for e in expected:
        for i, g in enumerate(got):
            if i not in used and g[0] == e[0] and g[1] == e[1] and dist(g[2], e[2]) < 0.5:
                used.add(i); t += 1; break
    tp += t; fn += len(expected) - t; fp += len(got) - t
    print(f'seed {seed}: expected {len(expected)}, reported {len(got)}, matched {t}')
    for i, g in enumerate(got):
        if i not in used: print('   extra', g[0], g[1], [round(x, 2) for x in g[2]])
    for e in expected:
        if not any(got[i][0] == e[0] and got[i][1] == e[1] and dist(got[i][2], e[2]) < 0.5 for i in used): print('   missed', e[0], e[1])
shutil.rmtree(work)
print(f'precision {tp / max(tp + fp, 1):.2f} recall {tp / max(tp + fn, 1):.2f} ({tp} of {tp + fn} found, {fp} extra)')
