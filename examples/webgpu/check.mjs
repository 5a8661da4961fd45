// Renders one exported preset — any number of passes, over a sequence of frames — through
// crt-webgpu.mjs's createCrtScene with Dawn (dawn.node from the npm package `webgpu` in
// tools/wgsl-runner) and writes the pixels, so a test can compare them with another renderer.
// Proves that the manifest (and the LUT files) alone are enough to drive the exported WGSL.
//
//   node examples/webgpu/check.mjs (--export DIR | --package APP_DIR) --preset NAME \
//        --input IN.raw --input-width W --input-height H \
//        --width W --height H --output OUT [--frames 0,1,...] [--capture 1,9] [--time SECONDS]
//        [--fit stretch|aspect|integer] [--set name=value ...] [--three on | --pixi on | --babylon on]
//
// --package: load the preset through the npm package `crtforge-presets` (an export's npm/ folder)
// as an app would, `import ... from 'crtforge-presets'` resolved from APP_DIR's node_modules, and
// its loadCrtPreset(); --export: read the export's files here and call createCrtScene.
// --three (with --package): through the package's three.js adapter instead (crtforge-presets/three
// on a three.js WebGPURenderer on the same Dawn device): the input, quantised to 8 bits, is drawn
// by three into a RenderTarget, the pass renders it into another (half float), read back.
// Each adapter's pass is made for its default format and renders into a half-float target, as an
// app may: the adapter makes a second scene for it, which must get the --set values too.
// --pixi (with --package): through the package's PixiJS adapter (crtforge-presets/pixi) on a PixiJS
// v8 WebGPURenderer: Pixi draws the 8-bit picture as a Sprite into a RenderTexture, the pass
// renders it into a half-float one. Pixi needs a core WebGPU adapter (its shaders interpolate
// `flat`), so this runs on Dawn's Vulkan backend on SwiftShader (Debian's chromium-common; lavapipe
// lacks a feature Dawn requires), where the others run on Dawn's GLES backend.
// --babylon (with --package): through the package's Babylon.js adapter (crtforge-presets/babylon)
// on a Babylon.js WebGPUEngine (Dawn's Vulkan backend too): Babylon uploads the 8-bit picture as a
// RawTexture, the pass renders it into a half-float RenderTargetTexture.
// RAW = little-endian float32 RGBA, rows top first. IN.raw holds one picture, or one per entry of
// --frames (the original at each frame drawn, in order). --frames defaults to 0; --capture (the
// frames written, default: the last drawn) writes OUT<frame>.raw each, or OUT itself when one
// frame is drawn and --capture is not given. --time pins every frame's time (default frame / fps).
// The input is uploaded as rgba16float when a pass filters the original linearly (rgba32float is
// not filterable on Dawn's GLES backend) and rgba32float otherwise; the target is rgba16float.
// Exit 0 on success; otherwise one line on stderr and exit 1 (bad arguments, unreadable files, no
// adapter, any Dawn validation/internal error).
//
// dawn.node prints its own noise on stdout; nothing here relies on stdout.
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createCrtScene, createLutTexture, mipmappedLuts } from './crt-webgpu.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, '../..');

function fail(message) {
  process.stderr.write(`check.mjs: ${String(message).replace(/\s*\n\s*/g, ' ').trim()}\n`);
  process.exit(1);
}

// A module of tools/wgsl-runner's pinned npm packages (webgpu, three, pixi.js, @babylonjs/core).
function importTool(specifier) {
  return import(pathToFileURL(createRequire(path.join(repo, 'tools/wgsl-runner/package.json')).resolve(specifier)).href);
}

// A module of the package under test, resolved from --package's app as the app would resolve it.
function importFromApp(specifier) {
  return import(pathToFileURL(createRequire(path.join(path.resolve(args.package), 'package.json')).resolve(specifier)).href);
}

function frameList(flag, text) {
  const frames = String(text).split(',').map(Number);
  if (!frames.length || !frames.every((f) => Number.isInteger(f) && f >= 0)) fail(`${flag} must be comma-separated frame numbers, got '${text}'`);
  return frames;
}

function parseArgs(argv) {
  const args = { time: undefined, set: [], frames: [0], capture: null, fit: undefined };
  const names = { '--export': 'export', '--package': 'package', '--preset': 'preset', '--input': 'input', '--input-width': 'inputWidth',
    '--input-height': 'inputHeight', '--width': 'width', '--height': 'height', '--output': 'output', '--time': 'time',
    '--fit': 'fit' };
  for (let i = 0; i < argv.length; i += 2) {
    const flag = argv[i], value = argv[i + 1];
    if (value === undefined) fail(`${flag} needs a value`);
    if (flag === '--set') args.set.push(value);
    else if (flag === '--frames') args.frames = frameList(flag, value);
    else if (flag === '--capture') args.capture = frameList(flag, value);
    else if (flag === '--three') args.three = value === 'on' ? true : fail(`--three takes 'on', got '${value}'`);
    else if (flag === '--pixi') args.pixi = value === 'on' ? true : fail(`--pixi takes 'on', got '${value}'`);
    else if (flag === '--babylon') args.babylon = value === 'on' ? true : fail(`--babylon takes 'on', got '${value}'`);
    else if (names[flag]) args[names[flag]] = value;
    else fail(`unknown argument '${flag}'`);
  }
  if ((args.export === undefined) === (args.package === undefined)) fail('give one of --export DIR and --package APP_DIR');
  if (args.three && args.package === undefined) fail('--three needs --package APP_DIR');
  const frameworks = ['three', 'pixi', 'babylon'].filter((f) => args[f]);
  if (frameworks.length && args.package === undefined) fail(`--${frameworks[0]} needs --package APP_DIR`);
  if (frameworks.length > 1) fail('give one of --three, --pixi and --babylon');
  for (const key of ['preset', 'input', 'inputWidth', 'inputHeight', 'width', 'height', 'output'])
    if (args[key] === undefined) fail(`missing --${key.replace(/[A-Z]/g, (c) => '-' + c.toLowerCase())}`);
  for (const key of ['inputWidth', 'inputHeight', 'width', 'height']) {
    const n = Number(args[key]);
    if (!Number.isInteger(n) || n < 1 || n > 16384) fail(`--${key} must be an integer 1..16384, got '${args[key]}'`);
    args[key] = n;
  }
  if (args.time !== undefined) {
    args.time = Number(args.time);
    if (!Number.isFinite(args.time)) fail('--time must be a number');
  }
  if (args.fit !== undefined && !['stretch', 'aspect', 'integer'].includes(args.fit)) fail(`--fit must be stretch, aspect or integer, got '${args.fit}'`);
  for (const f of args.capture ?? []) if (!args.frames.includes(f)) fail(`--capture frame ${f} is not in --frames`);
  return args;
}

// The RGBA8 texels of a PNG (8-bit RGBA or RGB, not interlaced: what crtforge writes and most
// LUT files are), with the filters of PNG's specification undone.
// float32 -> IEEE half bits, round to nearest even (what a GPU upload of the same values would do).
function toHalf(f32, u32, x) {
  f32[0] = x;
  const bits = u32[0], sign = (bits >>> 16) & 0x8000, exp = (bits >>> 23) & 0xff;
  let mant = bits & 0x7fffff;
  if (exp === 0xff) return sign | 0x7c00 | (mant ? 0x200 : 0);
  if (exp > 142) return sign | 0x7c00;
  if (exp >= 113) {
    let half = ((exp - 112) << 10) | (mant >>> 13);
    const rest = mant & 0x1fff;
    if (rest > 0x1000 || (rest === 0x1000 && (half & 1))) half += 1;
    return sign | half;
  }
  if (exp < 102) return sign;
  mant |= 0x800000;
  const shift = 126 - exp;
  let half = mant >>> shift;
  const rest = mant & ((1 << shift) - 1), halfway = 1 << (shift - 1);
  if (rest > halfway || (rest === halfway && (half & 1))) half += 1;
  return sign | half;
}

function fromHalf(h) {
  const sign = h & 0x8000 ? -1 : 1, exp = (h >>> 10) & 0x1f, mant = h & 0x3ff;
  if (exp === 0) return sign * mant * 2 ** -24;
  if (exp === 0x1f) return mant ? NaN : sign * Infinity;
  return sign * (1 + mant / 1024) * 2 ** (exp - 15);
}

const args = parseArgs(process.argv.slice(2));

// ---- the export: manifest, each pass's WGSL, the LUTs (or the package that holds them) ----
let manifest, preset, pkg;
const wgsl = {}, lutBytes = {};
if (args.package !== undefined) {
  try {
    pkg = await importFromApp('crtforge-presets');
    manifest = await pkg.loadManifest();
  } catch (e) {
    fail(`cannot load the package 'crtforge-presets' from ${args.package}: ${e.message}`);
  }
} else {
  try {
    manifest = JSON.parse(readFileSync(path.join(args.export, 'manifest.json'), 'utf8'));
  } catch (e) {
    fail(`cannot read ${path.join(args.export, 'manifest.json')}: ${e.message}`);
  }
}
preset = manifest.presets?.[args.preset];
if (!preset) fail(`preset '${args.preset}' is not in the manifest (${Object.keys(manifest.presets ?? {}).join(', ')})`);
for (const pass of args.export === undefined ? [] : preset.passes ?? []) {
  if (!pass.targets?.wgsl) fail(`preset '${args.preset}' has no wgsl target in the manifest (export with --target wgsl)`);
  try {
    wgsl[pass.alias] = readFileSync(path.join(args.export, pass.targets.wgsl.shader), 'utf8');
  } catch (e) {
    fail(`cannot read the WGSL of pass ${pass.alias}: ${e.message}`);
  }
}
for (const [name, lut] of Object.entries(args.export === undefined ? {} : preset.luts ?? {})) {
  try {
    lutBytes[name] = readFileSync(path.join(args.export, lut.file));
  } catch (e) {
    fail(`cannot read LUT ${name}: ${e.message}`);
  }
}

// ---- the input pictures: one, or one per frame drawn ----
let pictures = [];
try {
  const bytes = readFileSync(args.input);
  const one = args.inputWidth * args.inputHeight * 16;
  if (bytes.length !== one && bytes.length !== one * args.frames.length)
    fail(`${args.input} holds ${bytes.length} bytes; ${args.inputWidth}x${args.inputHeight} RGBA float32 needs ${one} (or ${one * args.frames.length} for ${args.frames.length} frames)`);
  const all = new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
  for (let i = 0; i < bytes.length / one; ++i) pictures.push(all.subarray(i * one / 4, (i + 1) * one / 4));
} catch (e) {
  fail(`cannot read the input: ${e.message}`);
}

// ---- Dawn (dawn.node) ----
process.env.EGL_PLATFORM ??= 'surfaceless';
let webgpu;
try {
  webgpu = await importTool('webgpu');
} catch (e) {
  fail(`cannot load the npm package 'webgpu' from tools/wgsl-runner (run scripts/setup.sh): ${e.message}`);
}
Object.assign(globalThis, webgpu.globals);
const kSwiftShaderIcd = '/usr/lib/chromium/vk_swiftshader_icd.json';
const core = args.pixi || args.babylon;  // frameworks that need a core adapter
if (core) process.env.VK_ICD_FILENAMES ??= kSwiftShaderIcd;  // read when Dawn opens Vulkan
const gpu = webgpu.create([core ? 'backend=vulkan' : 'backend=opengles']);
let device, pixiRenderer, babylonEngine;
if (args.pixi) {
  pixiRenderer = await startPixi();
  device = pixiRenderer.gpu.device;
} else if (args.babylon) {
  babylonEngine = await startBabylon();
  device = babylonEngine._device;
} else {
  const adapter = await gpu.requestAdapter({ featureLevel: 'compatibility' });
  if (!adapter) fail(`Dawn found no OpenGL ES adapter (EGL_PLATFORM=${process.env.EGL_PLATFORM})`);
  device = await adapter.requestDevice({
    requiredLimits: { maxTextureDimension2D: adapter.limits.maxTextureDimension2D },
  });
}
const uncaptured = [];
device.addEventListener('uncapturederror', (event) => uncaptured.push(event.error?.message ?? 'uncaptured error'));

let exitCode = 0;
try {
  device.pushErrorScope('out-of-memory');
  device.pushErrorScope('internal');
  device.pushErrorScope('validation');
  let failure = null, result = null;
  try {
    result = await render();
  } catch (e) {
    failure = e.message;
  }
  const scoped = [];
  for (let i = 0; i < 3; ++i) {
    const error = await device.popErrorScope();
    if (error) scoped.push(error.message);
  }
  const error = failure ?? scoped[0] ?? uncaptured[0];
  if (error) throw new Error(error);
  for (const { frame, buffer } of result) {
    const single = args.capture === null && args.frames.length === 1;
    writeFileSync(single ? args.output : `${args.output}${frame}.raw`, new Uint8Array(buffer));
  }
} catch (e) {
  process.stderr.write(`check.mjs: ${args.preset}: ${String(e.message).replace(/\s*\n\s*/g, ' ').trim()}\n`);
  exitCode = 1;
}
device.destroy();
process.exit(exitCode);  // dawn.node keeps the event loop alive on its own

// --set name=value (a colour as r,g,b) on a scene or a three.js pass.
function applySets(crt) {
  for (const assignment of args.set) {
    const [name, text] = assignment.split('=');
    crt.setParam(name, text.includes(',') ? text.split(',').map(Number) : Number(text));
  }
}

// The browser globals a framework reads while it starts in Node: navigator.gpu (Dawn), `self`,
// window event listeners, and an animation-frame clock (unused: frames are drawn by hand).
function installBrowserGlobals() {
  if (!globalThis.navigator?.gpu) Object.defineProperty(globalThis, 'navigator', { value: { gpu, userAgent: 'node' }, configurable: true });
  globalThis.self ??= globalThis;
  globalThis.addEventListener ??= () => {};
  globalThis.removeEventListener ??= () => {};
  globalThis.requestAnimationFrame ??= (callback) => setTimeout(() => callback(performance.now()), 16);
  globalThis.cancelAnimationFrame ??= (id) => clearTimeout(id);
}

// A canvas of the display's size that is never shown; `contexts` maps getContext's kinds to what
// it returns.
function canvasStandIn(width, height, contexts) {
  return { width, height, style: {}, addEventListener() {}, removeEventListener() {},
    getBoundingClientRect: () => ({ left: 0, top: 0, x: 0, y: 0, width, height, right: width, bottom: height }),
    getContext: (kind) => contexts[kind] ?? null };
}

// A WebGPU canvas context for frameworks that configure one but never present to it here (a
// function, not a constant: startPixi() runs while the module's top level is still evaluating).
function presentlessContext() {
  return { configure() {}, unconfigure() {}, getCurrentTexture() { throw new Error('no canvas in Node'); } };
}

// The package's three.js adapter: three draws the picture (8-bit, rows bottom-up as three's
// DataTexture takes them) into a RenderTarget, the crtforge pass draws that into a half-float one.
async function renderThree() {
  // three picks its WebGPU backend when navigator.gpu exists (Node 20 has no navigator).
  installBrowserGlobals();
  const THREE = await importTool('three/webgpu');
  const { createThreeCrtPass } = await importFromApp('crtforge-presets/three');
  // Nothing is presented: everything goes through RenderTargets.
  const canvas = canvasStandIn(args.width, args.height, { webgpu: presentlessContext() });
  const renderer = new THREE.WebGPURenderer({ canvas, device, antialias: false });
  await renderer.init();
  const w = args.inputWidth, h = args.inputHeight;
  const bytes = new Uint8Array(w * h * 4);
  const input = new THREE.RenderTarget(w, h, { depthBuffer: false });
  const output = new THREE.RenderTarget(args.width, args.height, { depthBuffer: false, type: THREE.HalfFloatType });
  const texture = new THREE.DataTexture(bytes, w, h, THREE.RGBAFormat, THREE.UnsignedByteType);
  Object.assign(texture, { colorSpace: THREE.NoColorSpace, magFilter: THREE.NearestFilter, minFilter: THREE.NearestFilter, generateMipmaps: false });
  const scene = new THREE.Scene();
  scene.add(new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.MeshBasicMaterial({ map: texture })));
  const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
  const crt = await createThreeCrtPass(renderer, args.preset);
  applySets(crt);
  return drawFrames(async (i, frame) => {
    const picture = pictures[Math.min(i, pictures.length - 1)];
    for (let y = 0; y < h; ++y)
      for (let x = 0; x < w * 4; ++x) bytes[(h - 1 - y) * w * 4 + x] = Math.round(Math.min(1, Math.max(0, picture[y * w * 4 + x])) * 255);
    texture.needsUpdate = true;
    renderer.setRenderTarget(input);
    await renderer.renderAsync(scene, camera);
    renderer.setRenderTarget(null);
    await crt.render(input, output, { frame, time: args.time, fit: args.fit });
    return crt.textureOf(output);
  });
}

// PixiJS v8 in Node: the few browser pieces its WebGPU renderer touches while it starts, stand-ins
// that draw nothing (its accessibility layer's DOM, a canvas, the WebGL context it asks for batch
// limits), and dawn.node made as lenient as browsers' WebIDL, which convert a numeric string to a
// number and treat a trailing `undefined` as an omitted argument (Pixi relies on both).
async function startPixi() {
  const element = () => ({ style: {}, children: [], setAttribute() {}, addEventListener() {}, removeEventListener() {}, appendChild() {}, removeChild() {}, remove() {} });
  globalThis.document ??= { createElement: element, body: element(), documentElement: element(), addEventListener() {}, removeEventListener() {} };
  installBrowserGlobals();
  const trim = (a) => { while (a.length && a[a.length - 1] === undefined) a.pop(); return a; };
  const lenient = (proto, name, slot) => {
    const original = proto[name];
    proto[name] = function (...a) {
      if (slot !== undefined && a[slot] !== undefined) a[slot] = Number(a[slot]);
      return original.apply(this, trim(a));
    };
  };
  for (const name of ['setVertexBuffer', 'setBindGroup']) lenient(GPURenderPassEncoder.prototype, name, 0);
  for (const name of ['setIndexBuffer', 'draw', 'drawIndexed', 'setViewport', 'setScissorRect']) lenient(GPURenderPassEncoder.prototype, name);
  lenient(GPUQueue.prototype, 'writeBuffer');
  const gl = { MAX_TEXTURE_IMAGE_UNITS: 0x8872, FRAGMENT_SHADER: 0x8b30, VERTEX_SHADER: 0x8b31, COMPILE_STATUS: 0x8b81, HIGH_FLOAT: 0x8df2,
    getParameter: () => 16, getExtension: () => null, isContextLost: () => false, createShader: () => ({}), shaderSource() {},
    compileShader() {}, getShaderParameter: () => true, deleteShader() {}, getShaderPrecisionFormat: () => ({ precision: 23, rangeMin: 127, rangeMax: 127 }) };
  const context = presentlessContext();
  const canvas = (width = 1, height = 1) => canvasStandIn(width, height, { webgpu: context, webgl: gl, webgl2: gl });
  const PIXI = await importTool('pixi.js');
  PIXI.DOMAdapter.set({
    createCanvas: canvas, getCanvasRenderingContext2D: () => class {}, getWebGLRenderingContext: () => class {},
    getNavigator: () => globalThis.navigator, getBaseUrl: () => pathToFileURL(repo).href, getFontFaceSet: () => null,
    fetch: (...a) => fetch(...a), parseXML: () => fail('Pixi asked to parse XML'),
  });
  const renderer = new PIXI.WebGPURenderer();
  await renderer.init({ width: args.width, height: args.height, canvas: canvas(args.width, args.height), resolution: 1, antialias: false,
    autoDensity: false, powerPreference: 'high-performance' });
  if (!renderer.gpu?.device) fail('PixiJS found no WebGPU device (Dawn on Vulkan: SwiftShader at ' + kSwiftShaderIcd + ')');
  renderer.pixi = PIXI;
  return renderer;
}

// The package's PixiJS adapter: Pixi draws the picture (8-bit) as a Sprite filling a RenderTexture,
// the crtforge pass draws that into a half-float RenderTexture, which is read back.
async function renderPixi() {
  const PIXI = pixiRenderer.pixi;
  const { createPixiCrtPass } = await importFromApp('crtforge-presets/pixi');
  const w = args.inputWidth, h = args.inputHeight;
  const bytes = new Uint8Array(w * h * 4);
  const picture = new PIXI.BufferImageSource({ resource: bytes, width: w, height: h, format: 'rgba8unorm', scaleMode: 'nearest', alphaMode: 'no-premultiply-alpha' });
  const sprite = new PIXI.Sprite(new PIXI.Texture({ source: picture }));
  const input = PIXI.RenderTexture.create({ width: w, height: h, scaleMode: 'nearest' });
  const output = PIXI.RenderTexture.create({ width: args.width, height: args.height, format: 'rgba16float' });
  const crt = await createPixiCrtPass(pixiRenderer, args.preset);
  applySets(crt);
  return drawFrames(async (i, frame) => {
    const pixels = pictures[Math.min(i, pictures.length - 1)];
    for (let k = 0; k < bytes.length; ++k) bytes[k] = Math.round(Math.min(1, Math.max(0, pixels[k])) * 255);
    picture.update();
    pixiRenderer.render({ container: sprite, target: input, clearColor: [0, 0, 0, 0] });
    await crt.render(input, output, { frame, time: args.time, fit: args.fit });
    return crt.textureOf(output);
  });
}

// Babylon.js's WebGPUEngine in Node: a canvas whose context hands out one texture as its current
// texture (nothing is presented), and the adapter's feature set given the forEach browsers have.
async function startBabylon() {
  const adapter = await gpu.requestAdapter();
  if (!adapter) fail('Dawn found no Vulkan adapter (SwiftShader at ' + kSwiftShaderIcd + ')');
  const features = Object.getPrototypeOf(adapter.features);
  features.forEach ??= function (callback, thisArg) { for (const f of this) callback.call(thisArg, f, f, this); };
  installBrowserGlobals();
  let config = null, backbuffer = null;
  const canvas = canvasStandIn(args.width, args.height, { webgpu: {
    configure(c) { config = c; backbuffer = null; }, unconfigure() { config = null; },
    getCurrentTexture() {
      backbuffer ??= config.device.createTexture({ size: [args.width, args.height], format: config.format, usage: config.usage ?? GPUTextureUsage.RENDER_ATTACHMENT });
      return backbuffer;
    },
  } });
  const BABYLON = await importTool('@babylonjs/core');
  BABYLON.Logger.LogLevels = BABYLON.Logger.ErrorLogLevel;
  const engine = new BABYLON.WebGPUEngine(canvas, { antialias: false, adaptToDeviceRatio: false });
  await engine.initAsync();
  engine.babylon = BABYLON;
  return engine;
}

// The package's Babylon.js adapter: Babylon uploads the picture (8-bit, nearest) as a RawTexture
// and draws it into a RenderTargetTexture (the game's frame, as an app renders its scene into one:
// recorded in Babylon's own encoder, which the adapter must flush first), the crtforge pass draws
// that into a half-float RenderTargetTexture, which is read back.
async function renderBabylon() {
  const BABYLON = babylonEngine.babylon;
  const { createBabylonCrtPass } = await importFromApp('crtforge-presets/babylon');
  const w = args.inputWidth, h = args.inputHeight;
  const scene = new BABYLON.Scene(babylonEngine);
  const bytes = new Uint8Array(w * h * 4);
  const picture = BABYLON.RawTexture.CreateRGBATexture(bytes, w, h, scene, false, false, BABYLON.Texture.NEAREST_SAMPLINGMODE);
  const input = new BABYLON.RenderTargetTexture('game', { width: w, height: h }, scene,
    { generateMipMaps: false, generateDepthBuffer: false, samplingMode: BABYLON.Texture.NEAREST_SAMPLINGMODE });
  const output = new BABYLON.RenderTargetTexture('crt', { width: args.width, height: args.height }, scene,
    { generateMipMaps: false, generateDepthBuffer: false, type: BABYLON.Constants.TEXTURETYPE_HALF_FLOAT });
  const draw = new BABYLON.CopyTextureToTexture(babylonEngine, false, true);  // texel for texel
  for (const deadline = Date.now() + 20000; !draw.isReady(); await new Promise((r) => setTimeout(r, 10)))
    if (Date.now() > deadline) throw new Error("Babylon's copy shader did not get ready within 20 s");
  const crt = await createBabylonCrtPass(babylonEngine, args.preset);
  applySets(crt);
  return drawFrames(async (i, frame) => {
    const pixels = pictures[Math.min(i, pictures.length - 1)];
    for (let k = 0; k < bytes.length; ++k) bytes[k] = Math.round(Math.min(1, Math.max(0, pixels[k])) * 255);
    picture.update(bytes);
    // Inside Babylon's frame, as from a render loop: what Babylon drew is not yet submitted.
    babylonEngine.beginFrame();
    if (!draw.copy(picture, input)) throw new Error('Babylon did not draw the picture into its RenderTargetTexture');
    await crt.render(input, output, { frame, time: args.time, fit: args.fit });
    babylonEngine.endFrame();
    return crt.textureOf(output);
  });
}

async function render() {
  if (args.three) return renderThree();
  if (args.pixi) return renderPixi();
  if (args.babylon) return renderBabylon();
  const linear = preset.passes.some((p) => p.textures.some((t) => /^original(@\d+)?$/.test(t.from) && t.filter !== 'nearest'));
  const inputFormat = linear ? 'rgba16float' : 'rgba32float';
  const source = device.createTexture({
    size: [args.inputWidth, args.inputHeight], format: inputFormat,
    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
  });
  const f32 = new Float32Array(1), u32 = new Uint32Array(f32.buffer);
  const upload = (pixels) => {
    const data = linear ? Uint16Array.from(pixels, (x) => toHalf(f32, u32, x)) : pixels;
    device.queue.writeTexture({ texture: source }, data, { bytesPerRow: args.inputWidth * (linear ? 8 : 16) }, [args.inputWidth, args.inputHeight]);
  };
  const target = device.createTexture({
    size: [args.width, args.height], format: 'rgba16float',
    usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC,
  });
  let crt;
  if (pkg) {
    crt = await pkg.loadCrtPreset(device, args.preset, { format: 'rgba16float' });
  } else {
    const luts = {};
    const mipmapped = mipmappedLuts(preset);
    for (const [name, bytes] of Object.entries(lutBytes))
      luts[name] = await createLutTexture(device, bytes, preset.luts[name].file, { mipmap: mipmapped.has(name) });
    crt = createCrtScene(device, { preset, wgsl, luts, format: 'rgba16float' });
  }
  for (const pass of crt.passes) {
    const compileError = (await pass.compilationInfo()).find((m) => m.type === 'error');
    if (compileError) throw new Error(`WGSL of pass ${pass.alias} ${compileError.lineNum}:${compileError.linePos}: ${compileError.message}`);
  }
  applySets(crt);

  return drawFrames((i, frame, encoder) => {
    upload(pictures[Math.min(i, pictures.length - 1)]);
    crt.encode(encoder, { source, target: target.createView(), width: args.width, height: args.height, frame, time: args.time, fit: args.fit });
    return target;
  });
}

// Draws each frame of --frames: `draw(index, frame, encoder)` records or submits the frame and
// returns the rgba16float texture it drew; the frames --capture names are copied out of it in the
// same encoder and read back.
async function drawFrames(draw) {
  const capture = args.capture ?? [args.frames[args.frames.length - 1]];
  const bytesPerRow = Math.ceil((args.width * 8) / 256) * 256;
  const out = [];
  for (let i = 0; i < args.frames.length; ++i) {
    const frame = args.frames[i];
    const encoder = device.createCommandEncoder();
    const texture = await draw(i, frame, encoder);
    let readback = null;
    if (capture.includes(frame)) {
      readback = device.createBuffer({ size: bytesPerRow * args.height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
      encoder.copyTextureToBuffer({ texture }, { buffer: readback, bytesPerRow, rowsPerImage: args.height }, [args.width, args.height]);
    }
    device.queue.submit([encoder.finish()]);
    await device.queue.onSubmittedWorkDone();
    if (readback) out.push({ frame, buffer: await readBack({ readback, bytesPerRow }) });
  }
  return out;
}

async function readBack({ readback, bytesPerRow }) {
  await readback.mapAsync(GPUMapMode.READ);
  const mapped = readback.getMappedRange();
  const rowValues = args.width * 4;
  const out = new Float32Array(rowValues * args.height);
  for (let y = 0; y < args.height; ++y) {
    const row = new Uint16Array(mapped, y * bytesPerRow, rowValues);
    for (let i = 0; i < rowValues; ++i) out[y * rowValues + i] = fromHalf(row[i]);
  }
  readback.unmap();
  return out.buffer;
}
