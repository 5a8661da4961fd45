// crtforge WGSL runner: a persistent Dawn (npm `webgpu`, dawn.node) process that compiles and
// renders WGSL for crtforge's Dawn engine (include/crtforge/dawn_engine.hpp). See README.md.
//
// Ops: info, compile (a module's messages), render (one pass from a described bind-group layout)
// and scene (a whole preset through an exported npm package, as an app runs it).
//
// Protocol: one JSON request per line on stdin, one JSON reply per line on the reply channel
// (stdout, or the descriptor given with --reply-fd=N). Every reply has "ok" and, when ok is
// false, "error" (one line) and "kind": "request" (malformed request, unreadable file) or
// "validation" (Dawn rejected the shader, the pipeline or the pass). The first reply, sent
// without a request, says whether start-up worked: {"ok":true,"ready":true,"info":{...}} or
// {"ok":false,"kind":"no-adapter"|"start","error":...} followed by exit code 3.
//
// dawn.node prints its own messages (start-up limit warnings, compilation logs, uncaptured
// errors) on STDOUT through C stdio, so a reply stream on stdout can be interleaved with them;
// the engine therefore passes --reply-fd and sends the process's stdout and stderr to a log.
import { readFileSync, writeFileSync, writeSync, closeSync } from 'node:fs';
import { createInterface } from 'node:readline';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

process.env.EGL_PLATFORM ??= 'surfaceless';  // Mesa EGL without a window system

let replyFd = 1;
let backend = 'opengles';
for (const arg of process.argv.slice(2)) {
  let m;
  if ((m = /^--reply-fd=(\d+)$/.exec(arg))) replyFd = Number(m[1]);
  else if ((m = /^--backend=([\w-]+)$/.exec(arg))) backend = m[1];
  else {
    process.stderr.write(`crtforge-wgsl-runner: unknown argument '${arg}'\n`);
    process.exit(2);
  }
}

function oneLine(text) {
  return String(text ?? '').replace(/\s*\n\s*/g, ' ').trim();
}

function reply(object) {
  // A leading newline keeps the reply on a line of its own even when it shares stdout with
  // Dawn's unterminated output; readers skip empty lines.
  const line = (replyFd === 1 ? '\n' : '') + JSON.stringify(object) + '\n';
  writeSync(replyFd, line);
}

class RequestError extends Error {}
class RejectError extends Error {
  constructor(message, extra = {}) {
    super(message);
    this.extra = extra;
  }
}

// ---- start-up ------------------------------------------------------------------------------

let gpu, adapter, device;
const uncaptured = [];  // device errors nobody caught with an error scope, drained per request
let lost = null;

async function start() {
  let webgpu;
  try {
    webgpu = await import('webgpu');
  } catch (e) {
    return { ok: false, kind: 'start', error: `cannot load the npm package 'webgpu' (run scripts/setup.sh): ${oneLine(e.message)}` };
  }
  Object.assign(globalThis, webgpu.globals);
  gpu = webgpu.create([`backend=${backend}`]);
  adapter = await gpu.requestAdapter({ featureLevel: 'compatibility' });
  if (!adapter)
    return {
      ok: false,
      kind: 'no-adapter',
      error: `Dawn found no '${backend}' adapter (EGL_PLATFORM is '${process.env.EGL_PLATFORM}')`,
    };
  const requiredFeatures = adapter.features.has('float32-filterable') ? ['float32-filterable'] : [];
  device = await adapter.requestDevice({
    requiredFeatures,
    requiredLimits: { maxTextureDimension2D: adapter.limits.maxTextureDimension2D },
  });
  device.addEventListener('uncapturederror', (event) => uncaptured.push(oneLine(event.error?.message)));
  device.lost.then((info) => {
    lost = oneLine(info.message) || info.reason || 'device lost';
  });
  return { ok: true, ready: true, info: adapterInfo() };
}

function adapterInfo() {
  const i = adapter.info;
  return {
    vendor: i.vendor ?? '',
    architecture: i.architecture ?? '',
    device: i.device ?? '',
    description: i.description ?? '',
    featureLevel: adapter.featureLevel ?? (adapter.features.has('core-features-and-limits') ? 'core' : 'compatibility'),
    backend,
    features: [...device.features].sort(),
    adapterFeatures: [...adapter.features].sort(),
    maxTextureDimension2D: device.limits.maxTextureDimension2D,
    float32Filterable: device.features.has('float32-filterable'),
  };
}

// ---- helpers -------------------------------------------------------------------------------

// `at` prefixes the key in errors, for fields of a nested object ("textures[1].").
function str(request, key, fallback, at = '') {
  const v = request[key] ?? fallback;
  if (typeof v !== 'string' || v === '') throw new RequestError(`"${at}${key}" must be a non-empty string`);
  return v;
}

function int(request, key, fallback, min, max, at = '') {
  const v = request[key] ?? fallback;
  if (!Number.isInteger(v) || v < min || v > max) throw new RequestError(`"${at}${key}" must be an integer in ${min}..${max}; got ${JSON.stringify(v)}`);
  return v;
}

function oneOf(request, key, fallback, allowed, at = '') {
  const v = str(request, key, fallback, at);
  if (!allowed.includes(v)) throw new RequestError(`"${at}${key}" must be one of ${allowed.map((a) => `'${a}'`).join(', ')}; got '${v}'`);
  return v;
}

function readBytes(path, what) {
  try {
    return readFileSync(path);
  } catch (e) {
    throw new RequestError(`cannot read the ${what} '${path}': ${oneLine(e.message)}`);
  }
}

function compilationMessages(info) {
  return info.messages.map((m) => ({
    type: m.type,
    lineNum: m.lineNum,
    linePos: m.linePos,
    message: oneLine(m.message),
  }));
}

// Runs `work` inside validation, internal and out-of-memory error scopes; the first error any of
// them (or the uncaptured-error listener) caught, or null.
async function withErrorScopes(work) {
  uncaptured.length = 0;
  device.pushErrorScope('out-of-memory');
  device.pushErrorScope('internal');
  device.pushErrorScope('validation');
  let thrown = null;
  let result;
  try {
    result = await work();
  } catch (e) {
    thrown = e;
  }
  const errors = [];
  for (let i = 0; i < 3; ++i) {
    const e = await device.popErrorScope();
    if (e) errors.push(oneLine(e.message));
  }
  if (thrown) throw thrown;
  errors.push(...uncaptured);
  uncaptured.length = 0;
  return { result, error: errors[0] ?? null };
}

// Shader modules and pipelines that compiled cleanly, kept for the next request with the same
// source (and, for pipelines, the same entry points, layout and format): creating a pipeline
// links a GL program, which is most of a small render's time on llvmpipe.
const CACHE_SIZE = 32;
const moduleCache = new Map();
const pipelineCache = new Map();

function remember(cache, key, value) {
  cache.delete(key);
  cache.set(key, value);
  if (cache.size > CACHE_SIZE) cache.delete(cache.keys().next().value);
  return value;
}

async function compileModule(path) {
  const code = readBytes(path, 'WGSL file').toString('utf8');
  const cached = moduleCache.get(code);
  if (cached) return remember(moduleCache, code, cached);
  const { result, error } = await withErrorScopes(async () => {
    const module = device.createShaderModule({ code });
    const info = await module.getCompilationInfo();
    return { module, messages: compilationMessages(info) };
  });
  const compiled = { ...result, error, code };
  if (!error && !compiled.messages.some((m) => m.type === 'error')) remember(moduleCache, code, compiled);
  return compiled;
}

// float32 -> IEEE half bits, round to nearest even; overflow goes to infinity, NaN stays NaN.
// Works on the float bits in bulk (a per-value Float32Array round trip is ~10x slower).
function floatsToHalves(floats) {
  const bits = new Uint32Array(floats.buffer, floats.byteOffset, floats.length);
  const out = new Uint16Array(floats.length);
  for (let i = 0; i < bits.length; ++i) {
    const x = bits[i];
    const sign = (x >>> 16) & 0x8000;
    const exp = (x >>> 23) & 0xff;
    let mant = x & 0x7fffff;
    let half;
    if (exp === 0xff) {
      half = 0x7c00 | (mant ? 0x200 : 0);
    } else if (exp > 142) {  // >= 2^16 after rounding: infinity
      half = 0x7c00;
    } else if (exp >= 113) {  // normal half
      half = ((exp - 112) << 10) | (mant >>> 13);
      const rest = mant & 0x1fff;
      if (rest > 0x1000 || (rest === 0x1000 && (half & 1))) half += 1;  // a carry into the exponent is right
    } else if (exp >= 102) {  // subnormal half
      mant |= 0x800000;
      const shift = 126 - exp;  // 14..24
      half = mant >>> shift;
      const rest = mant & ((1 << shift) - 1);
      const halfway = 1 << (shift - 1);
      if (rest > halfway || (rest === halfway && (half & 1))) half += 1;
    } else {
      half = 0;
    }
    out[i] = sign | half;
  }
  return out;
}

function halfToFloat(h) {
  const sign = h & 0x8000 ? -1 : 1;
  const exp = (h >>> 10) & 0x1f;
  const mant = h & 0x3ff;
  if (exp === 0) return sign * mant * 2 ** -24;
  if (exp === 0x1f) return mant ? NaN : sign * Infinity;
  return sign * (1 + mant / 1024) * 2 ** (exp - 15);
}

const HALF_TO_FLOAT = new Float32Array(65536).map((_, h) => halfToFloat(h));

function srgbToLinear(byte) {
  const c = byte / 255;
  return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
}

const FILTERS = ['nearest', 'linear'];
const ADDRESS_MODES = ['clamp-to-edge', 'repeat', 'mirror-repeat'];

// One texture to sample, read from `spec`: its bindings, filter, address mode and pixels (raw
// float32 RGBA rows, top first, from the file named by its image key; none = 1x1 transparent
// black). `keys` renames fields (the input's live at the request's top level under older names).
function readTexture(spec, keys, defaults, maxDim, at = '') {
  const texture = {
    binding: int(spec, keys.binding ?? 'binding', defaults.binding, 0, 1000, at),
    samplerBinding: int(spec, keys.samplerBinding ?? 'sampler_binding', defaults.samplerBinding, 0, 1000, at),
    filter: oneOf(spec, 'filter', 'linear', FILTERS, at),
    wrap: oneOf(spec, 'wrap', 'clamp-to-edge', ADDRESS_MODES, at),
    mipmap: spec.mipmap === true,
    mipFilter: oneOf(spec, 'mip_filter', 'linear', FILTERS, at),
    unorm8: spec.unorm8 === true,
    width: 1,
    height: 1,
    pixels: new Float32Array(4),
  };
  const imageKey = keys.image ?? 'image';
  if (spec[imageKey] != null) {
    const widthKey = keys.width ?? 'width', heightKey = keys.height ?? 'height';
    texture.width = int(spec, widthKey, undefined, 1, maxDim, at);
    texture.height = int(spec, heightKey, undefined, 1, maxDim, at);
    const bytes = readBytes(str(spec, imageKey, undefined, at), `${at}${imageKey} image`);
    const expected = texture.width * texture.height * 16;
    if (bytes.length !== expected)
      throw new RequestError(`the ${at}${imageKey} image holds ${bytes.length} bytes; ${texture.width}x${texture.height} RGBA float32 needs ${expected}`);
    texture.pixels = new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
  }
  return texture;
}

// The shipped WebGPU driver (its mip chains), loaded once, on the first texture that needs it.
let driver = null;
function shippedDriver() {
  driver ??= import('../../examples/webgpu/crt-webgpu.mjs');
  return driver;
}

// The one upload path of the input and of every extra texture. rgba32float when it can be
// sampled with the filter (nearest always: as unfilterable-float with a non-filtering sampler);
// otherwise rgba16float converted here. With `mipmap`, its mip chain is made by the shipped
// driver's encodeMipmaps (linear blits: a filterable format), in rgba8unorm for an 8-bit picture
// (`unorm8`: each level rounded to 8 bits, as RetroArch's chains are). Adds its layout and bind
// group entries; returns the format.
async function addSampledTexture(t, visibility, layoutEntries, groupEntries, destroy) {
  const linear = t.filter === 'linear';
  const bytes8 = t.mipmap && t.unorm8;
  const float32 = !bytes8 && ((!linear && !t.mipmap) || device.features.has('float32-filterable'));
  const format = bytes8 ? 'rgba8unorm' : float32 ? 'rgba32float' : 'rgba16float';
  const { mipLevelCount, encodeMipmaps } = await shippedDriver();
  const levels = t.mipmap ? mipLevelCount(t.width, t.height) : 1;
  const texture = device.createTexture({
    size: [t.width, t.height],
    format,
    mipLevelCount: levels,
    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | (levels > 1 ? GPUTextureUsage.RENDER_ATTACHMENT : 0),
  });
  destroy.push(texture);
  let data = t.pixels, bytesPerPixel = 16;
  if (bytes8) {
    data = Uint8Array.from(t.pixels, (v) => (v > 0 ? Math.round(Math.min(v, 1) * 255) : 0));
    bytesPerPixel = 4;
  } else if (!float32) {
    data = floatsToHalves(t.pixels);
    bytesPerPixel = 8;
  }
  device.queue.writeTexture({ texture }, data, { bytesPerRow: t.width * bytesPerPixel, rowsPerImage: t.height }, [t.width, t.height]);
  if (levels > 1) {
    const encoder = device.createCommandEncoder();
    encodeMipmaps(device, encoder, texture);
    device.queue.submit([encoder.finish()]);
  }
  const sampler = device.createSampler({
    magFilter: t.filter, minFilter: t.filter, mipmapFilter: t.mipmap ? t.mipFilter : 'nearest',
    addressModeU: t.wrap, addressModeV: t.wrap,
  });
  // A blend of mip levels counts as filtering in WebGPU.
  const filtering = linear || (t.mipmap && t.mipFilter === 'linear');
  layoutEntries.push({ binding: t.binding, visibility, texture: { sampleType: float32 && !filtering ? 'unfilterable-float' : 'float' } });
  layoutEntries.push({ binding: t.samplerBinding, visibility, sampler: { type: filtering ? 'filtering' : 'non-filtering' } });
  groupEntries.push({ binding: t.binding, resource: texture.createView() });
  groupEntries.push({ binding: t.samplerBinding, resource: sampler });
  return format;
}

// Each target format: its texel's bytes and how one texel (at byte `at` of a DataView) reads as
// linear RGBA. A channel the format lacks reads 0 (colour) or 1 (alpha), as a sampler returns it.
const halvesOf = (channels) => (v, at, out, o) => {
  for (let c = 0; c < 4; ++c) out[o + c] = c < channels ? HALF_TO_FLOAT[v.getUint16(at + 2 * c, true)] : c === 3 ? 1 : 0;
};
const OUTPUT_FORMATS = {
  rgba16float: { gpu: 'rgba16float', bytes: 8, texel: halvesOf(4) },
  rgba8unorm: { gpu: 'rgba8unorm', bytes: 4, texel: (v, at, out, o) => { for (let c = 0; c < 4; ++c) out[o + c] = v.getUint8(at + c) / 255; } },
  'rgba8unorm-srgb': {
    gpu: 'rgba8unorm-srgb', bytes: 4,
    texel: (v, at, out, o) => { for (let c = 0; c < 4; ++c) out[o + c] = c === 3 ? v.getUint8(at + c) / 255 : srgbToLinear(v.getUint8(at + c)); },
  },
  rgba32float: { gpu: 'rgba32float', bytes: 16, texel: (v, at, out, o) => { for (let c = 0; c < 4; ++c) out[o + c] = v.getFloat32(at + 4 * c, true); } },
  // One little-endian word: red in bits 0-9, green 10-19, blue 20-29, alpha 30-31.
  rgb10a2unorm: {
    gpu: 'rgb10a2unorm', bytes: 4,
    texel: (v, at, out, o) => {
      const word = v.getUint32(at, true);
      for (let c = 0; c < 3; ++c) out[o + c] = ((word >>> (10 * c)) & 0x3ff) / 1023;
      out[o + 3] = (word >>> 30) / 3;
    },
  },
  r16float: { gpu: 'r16float', bytes: 2, texel: halvesOf(1) },
  rg16float: { gpu: 'rg16float', bytes: 4, texel: halvesOf(2) },
};

// A mapped readback buffer (rows bytesPerRow apart) as linear float32 RGBA, rows top first.
function decodeRows(mapped, bytesPerRow, width, height, format) {
  const out = new Float32Array(width * height * 4);
  const view = new DataView(mapped.buffer, mapped.byteOffset, mapped.byteLength);
  for (let y = 0; y < height; ++y) {
    for (let x = 0; x < width; ++x) format.texel(view, y * bytesPerRow + x * format.bytes, out, (y * width + x) * 4);
  }
  return out;
}

function outputFormat(request) {
  const formatName = str(request, 'format', 'rgba16float');
  const format = OUTPUT_FORMATS[formatName];
  if (!format) throw new RequestError(`"format" must be one of ${Object.keys(OUTPUT_FORMATS).join(', ')}; got '${formatName}'`);
  return format;
}

// ---- requests ------------------------------------------------------------------------------

async function opCompile(request) {
  const { messages, error } = await compileModule(str(request, 'wgsl'));
  // A device error the compilation info does not show (none seen so far) becomes a message.
  if (error && !messages.some((m) => m.type === 'error')) messages.push({ type: 'error', lineNum: 0, linePos: 0, message: error });
  return { ok: true, messages };
}

async function opRender(request) {
  const wgsl = str(request, 'wgsl');
  const vertexEntry = str(request, 'vertex_entry', 'vs_main');
  const fragmentEntry = str(request, 'fragment_entry', 'fs_main');
  const maxDim = device.limits.maxTextureDimension2D;
  const width = int(request, 'width', undefined, 1, maxDim);
  const height = int(request, 'height', undefined, 1, maxDim);
  const format = outputFormat(request);
  const output = str(request, 'output');
  const uniformPath = request.uniform ?? null;
  if (uniformPath !== null && (typeof uniformPath !== 'string' || uniformPath === '')) throw new RequestError('"uniform" must be a path or null');
  const usesTexture = request.texture ?? true;
  if (typeof usesTexture !== 'boolean') throw new RequestError('"texture" must be true or false');
  const uniformBinding = int(request, 'uniform_binding', 0, 0, 1000);
  // The input: its fields sit at the top level of the request.
  const input = usesTexture
    ? readTexture(request, { binding: 'texture_binding', image: 'input', width: 'input_width', height: 'input_height' },
      { binding: 1, samplerBinding: 2 }, maxDim)
    : null;
  const textureSpecs = request.textures ?? [];
  if (!Array.isArray(textureSpecs)) throw new RequestError('"textures" must be an array');
  const textures = textureSpecs.map((spec, i) => {
    const at = `textures[${i}].`;
    if (spec === null || typeof spec !== 'object' || Array.isArray(spec)) throw new RequestError(`"textures[${i}]" must be an object`);
    return readTexture(spec, {}, {}, maxDim, at);
  });
  const used = [
    ...(uniformPath ? [uniformBinding] : []),
    ...[...(input ? [input] : []), ...textures].flatMap((t) => [t.binding, t.samplerBinding]),
  ];
  if (new Set(used).size !== used.length) throw new RequestError(`the bindings ${used.join(', ')} must differ`);

  // The rectangle drawn in (x, y, width, height; rows from the top), and the clear colour.
  let viewport = [0, 0, width, height];
  if (request.viewport != null) {
    const v = request.viewport;
    if (!Array.isArray(v) || v.length !== 4 || !v.every(Number.isInteger) || v[0] < 0 || v[1] < 0 || v[2] < 1 ||
        v[3] < 1 || v[0] + v[2] > width || v[1] + v[3] > height)
      throw new RequestError(`"viewport" must be [x, y, width, height] inside the ${width}x${height} target; got ${JSON.stringify(v)}`);
    viewport = v;
  }
  const clear = request.clear ?? [0, 0, 0, 0];
  if (!Array.isArray(clear) || clear.length !== 4 || !clear.every((c) => typeof c === 'number' && Number.isFinite(c)))
    throw new RequestError(`"clear" must be 4 finite numbers; got ${JSON.stringify(clear)}`);
  let uniformBytes = null;
  if (uniformPath) {
    uniformBytes = readBytes(uniformPath, 'uniform buffer');
    if (uniformBytes.length === 0) throw new RequestError('the uniform buffer file is empty');
  }

  const { module, messages, error: moduleError, code } = await compileModule(wgsl);
  const firstError = messages.find((m) => m.type === 'error');
  if (firstError)
    throw new RejectError(`${firstError.lineNum}:${firstError.linePos}: ${firstError.message}`, {
      messages, line: firstError.lineNum, column: firstError.linePos,
    });
  if (moduleError) throw new RejectError(moduleError, { messages });

  const { result, error } = await withErrorScopes(async () => {
    const visibility = GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT;
    const layoutEntries = [];
    const groupEntries = [];
    const destroy = [];
    if (uniformBytes) {
      const size = Math.max(16, Math.ceil(uniformBytes.length / 16) * 16);
      const padded = new Uint8Array(size);
      padded.set(uniformBytes);
      const buffer = device.createBuffer({ size, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
      destroy.push(buffer);
      device.queue.writeBuffer(buffer, 0, padded);
      layoutEntries.push({ binding: uniformBinding, visibility, buffer: { type: 'uniform' } });
      // The binding covers exactly the bytes given, so a block larger than the data is refused.
      groupEntries.push({ binding: uniformBinding, resource: { buffer, offset: 0, size: Math.ceil(uniformBytes.length / 4) * 4 } });
    }
    // One after another: the layout's entries keep the input's and the textures' order.
    const inputFormat = input ? await addSampledTexture(input, visibility, layoutEntries, groupEntries, destroy) : null;
    const textureFormats = [];
    for (const t of textures) textureFormats.push(await addSampledTexture(t, visibility, layoutEntries, groupEntries, destroy));
    const pipelineKey = JSON.stringify([code, vertexEntry, fragmentEntry, format.gpu, layoutEntries]);
    let { bindGroupLayout, pipeline } = pipelineCache.get(pipelineKey) ?? {};
    if (!pipeline) {
      bindGroupLayout = device.createBindGroupLayout({ entries: layoutEntries });
      pipeline = await device.createRenderPipelineAsync({
        layout: device.createPipelineLayout({ bindGroupLayouts: [bindGroupLayout] }),
        vertex: { module, entryPoint: vertexEntry },
        fragment: { module, entryPoint: fragmentEntry, targets: [{ format: format.gpu }] },
        primitive: { topology: 'triangle-list' },
      });
    }
    const bindGroup = device.createBindGroup({ layout: bindGroupLayout, entries: groupEntries });
    const target = device.createTexture({
      size: [width, height],
      format: format.gpu,
      usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC,
    });
    destroy.push(target);
    const bytesPerRow = Math.ceil((width * format.bytes) / 256) * 256;
    const readback = device.createBuffer({ size: bytesPerRow * height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
    destroy.push(readback);
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: target.createView(), loadOp: 'clear', storeOp: 'store', clearValue: clear }],
    });
    pass.setPipeline(pipeline);
    pass.setViewport(viewport[0], viewport[1], viewport[2], viewport[3], 0, 1);
    pass.setScissorRect(viewport[0], viewport[1], viewport[2], viewport[3]);
    pass.setBindGroup(0, bindGroup);
    pass.draw(3);
    pass.end();
    encoder.copyTextureToBuffer({ texture: target }, { buffer: readback, bytesPerRow, rowsPerImage: height }, [width, height]);
    device.queue.submit([encoder.finish()]);
    await device.queue.onSubmittedWorkDone();
    return {
      readback, bytesPerRow, destroy, inputFormat, textureFormats,
      cache: () => remember(pipelineCache, pipelineKey, { bindGroupLayout, pipeline }),
    };
  }).catch((e) => ({ result: null, error: oneLine(e.message) }));

  const cleanup = () => result?.destroy.forEach((o) => o.destroy());
  if (error) {
    cleanup();
    throw new RejectError(error, { messages });
  }
  result.cache();  // the pipeline, the bind group and the pass were all valid
  const { readback, bytesPerRow, inputFormat, textureFormats } = result;
  try {
    await readback.mapAsync(GPUMapMode.READ);
  } catch (e) {
    cleanup();
    throw new RejectError(`reading the pixels back failed: ${oneLine(e.message)}`, { messages });
  }
  const out = decodeRows(new Uint8Array(readback.getMappedRange()), bytesPerRow, width, height, format);
  readback.unmap();
  cleanup();
  try {
    writeFileSync(output, new Uint8Array(out.buffer));
  } catch (e) {
    throw new RequestError(`cannot write the output '${output}': ${oneLine(e.message)}`);
  }
  return { ok: true, messages, width, height, input_format: inputFormat, texture_formats: textureFormats };
}

// ---- a whole preset through the shipped npm package ------------------------------------------

function frameList(request, key) {
  const v = request[key];
  if (!Array.isArray(v) || !v.length || !v.every((f) => Number.isInteger(f) && f >= 0 && f <= 2 ** 31))
    throw new RequestError(`"${key}" must be a non-empty array of frame numbers; got ${JSON.stringify(v)}`);
  return v;
}

// Runs a preset as a page or a Node app does: the package folder an export writes (npm/) is
// imported, loadCrtPreset() reads its manifest, WGSL and LUT files and makes the scene, and each
// frame of `run` is one scene.encode() over that frame's original. Nothing of crtforge's own
// pipeline logic is here: pass sizes, feedback, history, uniforms and time are the package's.
async function opScene(request) {
  const dir = str(request, 'package');
  const presetName = str(request, 'preset');
  const maxDim = device.limits.maxTextureDimension2D;
  const width = int(request, 'width', undefined, 1, maxDim);
  const height = int(request, 'height', undefined, 1, maxDim);
  const format = outputFormat(request);
  const inputWidth = int(request, 'input_width', undefined, 1, maxDim);
  const inputHeight = int(request, 'input_height', undefined, 1, maxDim);
  const run = frameList(request, 'run');
  const capture = frameList(request, 'capture');
  for (const f of capture) if (!run.includes(f)) throw new RequestError(`"capture" frame ${f} is not in "run"`);
  const times = request.times ?? null;
  if (times !== null && (!Array.isArray(times) || times.length !== run.length || !times.every(Number.isFinite)))
    throw new RequestError(`"times" must be null or ${run.length} finite numbers`);
  const fit = request.fit ?? undefined;
  if (fit !== undefined && !['stretch', 'aspect', 'integer'].includes(fit)) throw new RequestError(`"fit" must be stretch, aspect or integer; got ${JSON.stringify(fit)}`);
  const params = request.params ?? {};
  if (params === null || typeof params !== 'object' || Array.isArray(params)) throw new RequestError('"params" must be an object');
  const inputs = readBytes(str(request, 'inputs'), 'inputs');
  const one = inputWidth * inputHeight * 16;
  if (inputs.length !== one * run.length)
    throw new RequestError(`the inputs hold ${inputs.length} bytes; ${run.length} pictures of ${inputWidth}x${inputHeight} RGBA float32 need ${one * run.length}`);
  const pictures = new Float32Array(inputs.buffer.slice(inputs.byteOffset, inputs.byteOffset + inputs.length));
  const output = str(request, 'output');

  let pkg;
  try {
    pkg = await import(pathToFileURL(path.join(path.resolve(dir), 'index.mjs')).href);
  } catch (e) {
    throw new RejectError(`the npm package in '${dir}' does not load: ${oneLine(e.message)}`);
  }
  const { result, error } = await withErrorScopes(async () => {
    const destroy = [];
    try {
      const manifest = await pkg.loadManifest();
      const preset = manifest.presets?.[presetName];
      if (!preset) throw new RejectError(`the package's manifest has no preset '${presetName}'`);
      const crt = await pkg.loadCrtPreset(device, presetName, { format: format.gpu });
      destroy.push(crt);
      for (const pass of crt.passes) {
        const bad = (await pass.compilationInfo()).find((m) => m.type === 'error');
        if (bad) throw new RejectError(`the WGSL of pass ${pass.alias}, ${bad.lineNum}:${bad.linePos}: ${oneLine(bad.message)}`);
      }
      for (const [name, value] of Object.entries(params)) crt.setParam(name, value);
      // The original as an app would upload float pictures: rgba32float where every pass that
      // reads it samples it nearest (or the device filters float32), else rgba16float.
      const linear = preset.passes.some((p) => p.textures.some((t) => /^original(@\d+)?$/.test(t.from) && t.filter !== 'nearest'));
      const half = linear && !device.features.has('float32-filterable');
      const source = device.createTexture({
        size: [inputWidth, inputHeight], format: half ? 'rgba16float' : 'rgba32float',
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST,
      });
      destroy.push(source);
      const target = device.createTexture({ size: [width, height], format: format.gpu, usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC });
      destroy.push(target);
      const bytesPerRow = Math.ceil((width * format.bytes) / 256) * 256;
      const images = [];
      for (let i = 0; i < run.length; ++i) {
        const picture = pictures.subarray((i * one) / 4, ((i + 1) * one) / 4);
        device.queue.writeTexture({ texture: source }, half ? floatsToHalves(picture) : picture,
          { bytesPerRow: inputWidth * (half ? 8 : 16), rowsPerImage: inputHeight }, [inputWidth, inputHeight]);
        const encoder = device.createCommandEncoder();
        crt.encode(encoder, { source, target: target.createView(), width, height, frame: run[i], fit, ...(times ? { time: times[i] } : {}) });
        let readback = null;
        if (capture.includes(run[i])) {
          readback = device.createBuffer({ size: bytesPerRow * height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
          destroy.push(readback);
          encoder.copyTextureToBuffer({ texture: target }, { buffer: readback, bytesPerRow, rowsPerImage: height }, [width, height]);
        }
        device.queue.submit([encoder.finish()]);
        await device.queue.onSubmittedWorkDone();
        if (readback) {
          await readback.mapAsync(GPUMapMode.READ);
          images.push({ frame: run[i], pixels: decodeRows(new Uint8Array(readback.getMappedRange()), bytesPerRow, width, height, format) });
          readback.unmap();
        }
      }
      return images;
    } finally {
      for (const o of destroy) o.destroy();
    }
  }).catch((e) => {
    if (e instanceof RequestError || e instanceof RejectError) throw e;
    return { result: null, error: oneLine(e.message) };
  });
  if (error) throw new RejectError(error);
  // The captured frames in the order "capture" lists them.
  const out = new Float32Array(capture.length * width * height * 4);
  capture.forEach((frame, k) => out.set(result.find((image) => image.frame === frame).pixels, k * width * height * 4));
  try {
    writeFileSync(output, new Uint8Array(out.buffer));
  } catch (e) {
    throw new RequestError(`cannot write the output '${output}': ${oneLine(e.message)}`);
  }
  return { ok: true, width, height, frames: capture.length };
}

async function handle(line) {
  let request;
  try {
    request = JSON.parse(line);
  } catch (e) {
    return { ok: false, kind: 'request', error: `the request is not JSON: ${oneLine(e.message)}` };
  }
  if (request === null || typeof request !== 'object' || Array.isArray(request))
    return { ok: false, kind: 'request', error: 'the request must be a JSON object' };
  const id = typeof request.id === 'number' || typeof request.id === 'string' ? { id: request.id } : {};
  return { ...(await dispatch(request)), ...id };
}

async function dispatch(request) {
  if (lost) return { ok: false, kind: 'validation', error: `the device was lost: ${lost}` };
  try {
    switch (request.op) {
      case 'info': return { ok: true, info: adapterInfo() };
      case 'compile': return await opCompile(request);
      case 'render': return await opRender(request);
      case 'scene': return await opScene(request);
      default: return { ok: false, kind: 'request', error: `unknown op ${JSON.stringify(request.op)} (expected compile, render, scene or info)` };
    }
  } catch (e) {
    if (e instanceof RequestError) return { ok: false, kind: 'request', error: e.message };
    if (e instanceof RejectError) return { ok: false, kind: 'validation', error: oneLine(e.message), ...e.extra };
    return { ok: false, kind: 'validation', error: oneLine(e?.message ?? e) };
  }
}

// ---- main loop -----------------------------------------------------------------------------

let started;
try {
  started = await start();
} catch (e) {
  started = { ok: false, kind: 'start', error: `Dawn failed to start: ${oneLine(e?.message ?? e)}` };
}
reply(started);
if (!started.ok) {
  process.exitCode = 3;
} else {
  const lines = createInterface({ input: process.stdin, crlfDelay: Infinity, terminal: false });
  for await (const line of lines) {
    if (line.trim() === '') continue;
    let answer;
    try {
      answer = await handle(line);
    } catch (e) {
      answer = { ok: false, kind: 'validation', error: oneLine(e?.message ?? e) };
    }
    reply(answer);
  }
  device.destroy();
}
if (replyFd !== 1) closeSync(replyFd);
// dawn.node keeps the event loop alive with its own handles; leave explicitly.
process.exit();
