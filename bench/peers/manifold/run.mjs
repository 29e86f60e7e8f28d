#!/usr/bin/env node
// Manifold (manifold-3d, WASM, one thread) as a peer boolean engine: evaluates the CSG program of
// PROGRAM.json (format in README.md) and prints one JSON line with its time and volume.
//   node run.mjs PROGRAM.json [--out RESULT.off] [--repeat N]
// Exit codes: 0 when a line is printed (status "ok" or "error"); 2 bad usage or malformed input
// file (one line on stderr); 1 --out could not be written; 3 manifold-3d is not installed.
import { readFileSync, writeFileSync, renameSync, unlinkSync } from 'node:fs';
import { dirname, join, basename } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const OPS = { union: 'add', intersection: 'intersect', difference: 'subtract' };
const BATCH = { union: 'union', intersection: 'intersection', difference: 'difference' };

function die(code, message) {
  process.stderr.write(`run.mjs: ${message.replace(/\s+/g, ' ')}\n`);
  process.exit(code);
}

// ---- command line ----
let programPath = null, outPath = null, repeat = 1;
{
  const args = process.argv.slice(2);
  for (let i = 0; i < args.length; i++) {
    const a = args[i];
    if (a === '--out' || a === '--repeat') {
      if (i + 1 >= args.length) die(2, `${a} needs a value`);
      const v = args[++i];
      if (a === '--out') outPath = v;
      else {
        if (!/^[1-9][0-9]*$/.test(v)) die(2, `--repeat wants a positive integer, not '${v}'`);
        repeat = Number(v);
      }
    } else if (a.startsWith('--')) {
      die(2, `unknown option ${a} (usage: node run.mjs PROGRAM.json [--out RESULT.off] [--repeat N])`);
    } else if (programPath === null) {
      programPath = a;
    } else {
      die(2, `one program file only ('${programPath}', then '${a}')`);
    }
  }
  if (programPath === null) die(2, 'usage: node run.mjs PROGRAM.json [--out RESULT.off] [--repeat N]');
}

// ---- input file: read and validate all before the engine sees any of it ----
function malformed(problem) { die(2, `${programPath}: ${problem}`); }

let doc;
{
  let text;
  try { text = readFileSync(programPath, 'utf8'); } catch (e) { malformed(`cannot read: ${e.code || e.message}`); }
  try { doc = JSON.parse(text); } catch (e) { malformed(`not JSON: ${e.message}`); }
}
const isObject = (x) => x !== null && typeof x === 'object' && !Array.isArray(x);
if (!isObject(doc)) malformed('top level is not an object');
if (!Array.isArray(doc.meshes)) malformed('"meshes" is missing or not an array');
if (!('program' in doc)) malformed('"program" is missing');
if ('batch' in doc && typeof doc.batch !== 'boolean') malformed('"batch" is not true or false');
const batch = doc.batch === true;

// Meshes become typed arrays here (float32 positions: the only vertex type manifold-3d's JS Mesh
// carries), outside the timing.
const meshes = doc.meshes.map((m, k) => {
  const where = `meshes[${k}]`;
  if (!isObject(m)) malformed(`${where} is not an object`);
  const { vertices: v, triangles: t } = m;
  if (!Array.isArray(v) || v.length % 3 !== 0) malformed(`${where}.vertices is not an array of 3n numbers`);
  if (!Array.isArray(t) || t.length % 3 !== 0) malformed(`${where}.triangles is not an array of 3n indices`);
  const nv = v.length / 3;
  const vertProperties = new Float32Array(v.length);
  for (let i = 0; i < v.length; i++) {
    if (typeof v[i] !== 'number') malformed(`${where}.vertices[${i}] is not a number`);
    vertProperties[i] = v[i];
  }
  const triVerts = new Uint32Array(t.length);
  for (let i = 0; i < t.length; i++) {
    const x = t[i];
    if (!Number.isInteger(x) || x < 0 || x >= nv)
      malformed(`${where}.triangles[${i}] = ${JSON.stringify(x)} is not a vertex index below ${nv}`);
    triVerts[i] = x;
  }
  return { vertProperties, triVerts };
});

// Validates the program tree; counts binary booleans (steps) and n-ary calls (batch), and lists
// the meshes it uses.
const used = new Set();
let steps = 0, batchCalls = 0;
function check(node, where, depth) {
  if (depth > 2000) malformed(`${where}: program nested too deep`);
  if (!isObject(node)) malformed(`${where} is not an object`);
  if ('mesh' in node) {
    if ('op' in node || 'children' in node) malformed(`${where} has both "mesh" and "op"/"children"`);
    const i = node.mesh;
    if (!Number.isInteger(i) || i < 0 || i >= meshes.length)
      malformed(`${where}.mesh = ${JSON.stringify(i)} is not an index below ${meshes.length}`);
    used.add(i);
    return;
  }
  if (!Object.hasOwn(OPS, node.op)) malformed(`${where}.op = ${JSON.stringify(node.op)} is not union, intersection or difference`);
  if (!Array.isArray(node.children)) malformed(`${where}.children is missing or not an array`);
  const n = node.children.length;
  if (n === 0 && node.op !== 'union') malformed(`${where}: ${node.op} with no children`);
  node.children.forEach((c, j) => check(c, `${where}.children[${j}]`, depth + 1));
  steps += Math.max(n - 1, 0);
  if (n >= 2) batchCalls += 1;
}
check(doc.program, 'program', 0);

// ---- engine ----
let wasm, version;
try {
  version = JSON.parse(readFileSync(join(here, 'node_modules/manifold-3d/package.json'), 'utf8')).version;
  const Module = (await import('manifold-3d')).default;
  wasm = await Module();
  wasm.setup();
} catch (e) {
  die(3, `manifold-3d is not installed here (npm ci --prefix ${here}): ${e.message}`);
}
const { Manifold, Mesh } = wasm;
const head = { engine: 'manifold', version, node: process.version, threads: 1 };

class EngineError extends Error {}
function statusOk(m, what) {
  const s = m.status();  // on a deferred CSG node this evaluates it
  if (s !== 'NoError') throw new EngineError(`${what}: ${s}`);
}

// One evaluation. Every WASM object it makes goes to `live` (freed by the caller) unless freed
// here once consumed; intermediates are freed as soon as the next step no longer needs them.
function evaluate(live) {
  const leaves = new Map();
  for (const i of [...used].sort((a, b) => a - b)) {
    const mesh = new Mesh({ numProp: 3, vertProperties: meshes[i].vertProperties, triVerts: meshes[i].triVerts });
    let m;
    try { m = new Manifold(mesh); } catch (e) {
      throw new EngineError(`input mesh ${i}: ${e.message}${e.code ? ` (${e.code})` : ''}`);
    }
    live.add(m);
    leaves.set(i, m);
  }
  const free = (m) => { if (live.delete(m)) m.delete(); };
  const owned = new Set();  // results of this evaluation (not input leaves), safe to free
  const release = (m) => { if (owned.delete(m)) free(m); };
  const make = (m) => { live.add(m); owned.add(m); return m; };
  const empty = () => make(new Manifold(new Mesh({ numProp: 3, vertProperties: new Float32Array(0), triVerts: new Uint32Array(0) })));

  function run(node) {
    if ('mesh' in node) return leaves.get(node.mesh);
    const kids = node.children;
    if (kids.length === 0) return empty();
    if (kids.length === 1) return run(kids[0]);
    if (batch) {
      const parts = kids.map(run);
      const r = make(Manifold[BATCH[node.op]](parts));
      parts.forEach(release);  // the C++ CSG node keeps what it needs
      return r;
    }
    let acc = run(kids[0]);
    for (let j = 1; j < kids.length; j++) {
      const b = run(kids[j]);
      const r = make(acc[OPS[node.op]](b));
      statusOk(r, `${node.op} step`);  // forces this binary boolean now: no lazy n-ary merging
      release(acc);
      release(b);
      acc = r;
    }
    return acc;
  }
  const result = run(doc.program);
  statusOk(result, 'result');
  const mesh = result.getMesh();
  return { result, mesh };
}

function median(xs) {
  const s = [...xs].sort((a, b) => a - b);
  const h = s.length >> 1;
  return s.length % 2 ? s[h] : (s[h - 1] + s[h]) / 2;
}

function writeOff(path, mesh) {
  const np = mesh.numProp, vp = mesh.vertProperties, nv = vp.length / np;
  // Positions split only for properties (none here with numProp 3, but be safe): merge them back.
  const to = new Uint32Array(nv);
  for (let i = 0; i < nv; i++) to[i] = i;
  const from = mesh.mergeFromVert || [], dest = mesh.mergeToVert || [];
  for (let i = 0; i < from.length; i++) to[from[i]] = dest[i];
  const index = new Int32Array(nv).fill(-1);
  const tri = mesh.triVerts, vlines = [], flines = [];
  for (let i = 0; i < tri.length; i += 3) {
    const f = [];
    for (let k = 0; k < 3; k++) {
      const v = to[tri[i + k]];
      if (index[v] < 0) {
        index[v] = vlines.length;
        vlines.push(`${vp[v * np]} ${vp[v * np + 1]} ${vp[v * np + 2]}`);
      }
      f.push(index[v]);
    }
    flines.push(`3 ${f[0]} ${f[1]} ${f[2]}`);
  }
  const text = `OFF\n${vlines.length} ${flines.length} 0\n${vlines.join('\n')}${vlines.length ? '\n' : ''}` +
    `${flines.join('\n')}${flines.length ? '\n' : ''}`;
  const tmp = join(dirname(path), `.${basename(path)}.${process.pid}.tmp`);
  try {
    writeFileSync(tmp, text);
    renameSync(tmp, path);
  } catch (e) {
    try { unlinkSync(tmp); } catch { /* never written */ }
    die(1, `cannot write ${path}: ${e.message}`);
  }
}

const secondsAll = [];
let final = null;
for (let r = 0; r < repeat; r++) {
  const live = new Set();
  let out;
  const t0 = performance.now();
  try {
    out = evaluate(live);
  } catch (e) {
    const message = e instanceof EngineError ? e.message : `${e && e.name ? e.name + ': ' : ''}${e && e.message ? e.message : String(e)}`;
    process.stdout.write(JSON.stringify({ ...head, batch, status: 'error', error: message, steps }) + '\n');
    process.exit(0);
  }
  secondsAll.push((performance.now() - t0) / 1000);
  if (r === repeat - 1) {
    final = {
      volume: out.result.volume(),
      triangles: out.mesh.numTri,
      vertices: out.result.numVert(),
      mesh: out.mesh,
    };
  }
  for (const m of live) m.delete();
}

if (outPath !== null) writeOff(outPath, final.mesh);
const line = {
  ...head, batch, status: 'ok',
  seconds: median(secondsAll), seconds_all: secondsAll,
  volume: final.volume, triangles: final.triangles, vertices: final.vertices,
  steps, ...(batch ? { batch_calls: batchCalls } : {}),
};
process.stdout.write(JSON.stringify(line) + '\n');
