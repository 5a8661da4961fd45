// Renders one exported preset through crt-webgpu.mjs with Dawn (dawn.node from the npm package
// `webgpu` in tools/wgsl-runner) and writes the pixels, so a test can compare them with another
// renderer. Proves that the manifest alone is enough to drive the exported WGSL.
//
//   node examples/webgpu/check.mjs --export DIR --preset NAME \
//        --input IN.raw --input-width W --input-height H \
//        --width W --height H --output OUT.raw [--time SECONDS] [--set name=value ...]
//
// RAW = little-endian float32 RGBA, rows top first. The input is uploaded as rgba16float for
// linear presets (rgba32float is not filterable on Dawn's GLES backend) and rgba32float for
// nearest ones; the target is rgba16float. Exit 0 on success; otherwise one line on stderr and
// exit 1 (bad arguments, unreadable files, no adapter, any Dawn validation/internal error).
//
// dawn.node prints its own noise on stdout; nothing here relies on stdout.
import { readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { createCrtPass } from './crt-webgpu.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const repo = path.resolve(here, '../..');

function fail(message) {
  process.stderr.write(`check.mjs: ${String(message).replace(/\s*\n\s*/g, ' ').trim()}\n`);
  process.exit(1);
}

function parseArgs(argv) {
  const args = { time: 0, set: [] };
  const names = { '--export': 'export', '--preset': 'preset', '--input': 'input', '--input-width': 'inputWidth',
    '--input-height': 'inputHeight', '--width': 'width', '--height': 'height', '--output': 'output', '--time': 'time' };
  for (let i = 0; i < argv.length; i += 2) {
    const flag = argv[i], value = argv[i + 1];
    if (value === undefined) fail(`${flag} needs a value`);
    if (flag === '--set') args.set.push(value);
    else if (names[flag]) args[names[flag]] = value;
    else fail(`unknown argument '${flag}'`);
  }
  for (const key of ['export', 'preset', 'input', 'inputWidth', 'inputHeight', 'width', 'height', 'output'])
    if (args[key] === undefined) fail(`missing --${key.replace(/[A-Z]/g, (c) => '-' + c.toLowerCase())}`);
  for (const key of ['inputWidth', 'inputHeight', 'width', 'height']) {
    const n = Number(args[key]);
    if (!Number.isInteger(n) || n < 1 || n > 16384) fail(`--${key} must be an integer 1..16384, got '${args[key]}'`);
    args[key] = n;
  }
  args.time = Number(args.time);
  if (!Number.isFinite(args.time)) fail('--time must be a number');
  return args;
}

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

// ---- the export: manifest + WGSL ----
let manifest, preset, wgsl;
try {
  manifest = JSON.parse(readFileSync(path.join(args.export, 'manifest.json'), 'utf8'));
} catch (e) {
  fail(`cannot read ${path.join(args.export, 'manifest.json')}: ${e.message}`);
}
preset = manifest.presets?.[args.preset];
if (!preset) fail(`preset '${args.preset}' is not in the manifest (${Object.keys(manifest.presets ?? {}).join(', ')})`);
if (preset.passes?.length !== 1) fail(`preset '${args.preset}' is a scene of ${preset.passes?.length} passes; this check runs single-pass presets`);
preset = preset.passes[0];
if (!preset.targets?.wgsl) fail(`preset '${args.preset}' has no wgsl target in the manifest (export with --target wgsl)`);
try {
  wgsl = readFileSync(path.join(args.export, preset.targets.wgsl.shader), 'utf8');
} catch (e) {
  fail(`cannot read the WGSL: ${e.message}`);
}

// ---- the input image ----
let pixels;
try {
  const bytes = readFileSync(args.input);
  const expected = args.inputWidth * args.inputHeight * 16;
  if (bytes.length !== expected) fail(`${args.input} holds ${bytes.length} bytes; ${args.inputWidth}x${args.inputHeight} RGBA float32 needs ${expected}`);
  pixels = new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
} catch (e) {
  fail(`cannot read the input: ${e.message}`);
}

// ---- Dawn (dawn.node) ----
process.env.EGL_PLATFORM ??= 'surfaceless';
let webgpu;
try {
  const require = createRequire(path.join(repo, 'tools/wgsl-runner/package.json'));
  webgpu = await import(pathToFileURL(require.resolve('webgpu')).href);
} catch (e) {
  fail(`cannot load the npm package 'webgpu' from tools/wgsl-runner (run scripts/setup.sh): ${e.message}`);
}
Object.assign(globalThis, webgpu.globals);
const gpu = webgpu.create(['backend=opengles']);
const adapter = await gpu.requestAdapter({ featureLevel: 'compatibility' });
if (!adapter) fail(`Dawn found no OpenGL ES adapter (EGL_PLATFORM=${process.env.EGL_PLATFORM})`);
const device = await adapter.requestDevice({
  requiredLimits: { maxTextureDimension2D: adapter.limits.maxTextureDimension2D },
});
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
  writeFileSync(args.output, new Uint8Array(await readBack(result)));
} catch (e) {
  process.stderr.write(`check.mjs: ${args.preset}: ${String(e.message).replace(/\s*\n\s*/g, ' ').trim()}\n`);
  exitCode = 1;
}
device.destroy();
process.exit(exitCode);  // dawn.node keeps the event loop alive on its own

async function render() {
  const linear = preset.textures?.[0]?.filter !== 'nearest';
  const inputFormat = linear ? 'rgba16float' : 'rgba32float';
  const source = device.createTexture({
    size: [args.inputWidth, args.inputHeight], format: inputFormat,
    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
  });
  let data = pixels, bytesPerPixel = 16;
  if (linear) {
    const f32 = new Float32Array(1), u32 = new Uint32Array(f32.buffer);
    data = Uint16Array.from(pixels, (x) => toHalf(f32, u32, x));
    bytesPerPixel = 8;
  }
  device.queue.writeTexture({ texture: source }, data, { bytesPerRow: args.inputWidth * bytesPerPixel }, [args.inputWidth, args.inputHeight]);

  const target = device.createTexture({
    size: [args.width, args.height], format: 'rgba16float',
    usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC,
  });
  const crt = createCrtPass(device, { wgsl, preset, format: 'rgba16float' });
  const compileError = (await crt.compilationInfo()).find((m) => m.type === 'error');
  if (compileError) throw new Error(`WGSL ${compileError.lineNum}:${compileError.linePos}: ${compileError.message}`);
  for (const assignment of args.set) {
    const [name, text] = assignment.split('=');
    crt.setParam(name, text.includes(',') ? text.split(',').map(Number) : Number(text));
  }

  const bytesPerRow = Math.ceil((args.width * 8) / 256) * 256;
  const readback = device.createBuffer({ size: bytesPerRow * args.height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
  const encoder = device.createCommandEncoder();
  crt.encode(encoder, { source, target: target.createView(), width: args.width, height: args.height, time: args.time });
  encoder.copyTextureToBuffer({ texture: target }, { buffer: readback, bytesPerRow, rowsPerImage: args.height }, [args.width, args.height]);
  device.queue.submit([encoder.finish()]);
  await device.queue.onSubmittedWorkDone();
  return { readback, bytesPerRow };
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
