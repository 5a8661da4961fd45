// crt-webgpu.mjs: run crtforge CRT presets with WebGPU — a single pass, or a whole scene of passes
// with feedback (a pass's previous frame), the original's history and lookup textures.
//
// Drop-in, dependency-free ES module. It works wherever WebGPU does: in a browser, or in Node with
// dawn.node (npm `webgpu`) once its `globals` are on globalThis. It reads GPUShaderStage,
// GPUBufferUsage and GPUTextureUsage from globalThis.
//
// Everything it needs comes from `crtforge export`: manifest.json's entry for the preset and the
// text of each pass's wgsl/<file>.wgsl.
//
//   // a whole preset (any number of passes):
//   const scene = createCrtScene(device, { preset: manifest.presets['super-win'], wgsl, luts, format });
//   scene.encode(encoder, { source, target: view, width, height, frame, time });
//       wgsl: { [pass alias]: WGSL text }, luts: { [lut name]: GPUTexture } (the PNGs of luts/)
//
//   // one pass:
//   const pass = createCrtPass(device, { wgsl, preset: manifest.presets.classic.passes[0], format });
//   pass.encode(encoder, { source, target: view, width, height, time });
//
// encode() writes uniform buffers with device.queue.writeBuffer, so the values in effect are the
// ones of the last encode() before the command buffer is submitted: submit once per frame.

// The WGSL half of a pass's manifest entry: bindings, entry points, uniform byte layout.
function wgslTarget(pass) {
  const target = pass?.targets?.wgsl;
  if (!target) throw new Error('crt-webgpu: the pass has no targets.wgsl entry (export with --target wgsl)');
  return target;
}

// 'f32' | 'vec3<f32>' | 'vec3f' -> { scalar: 'f32', count: 3 }
function parseType(type) {
  let m = /^vec([234])<(f32|i32|u32)>$/.exec(type);
  if (m) return { scalar: m[2], count: Number(m[1]) };
  m = /^vec([234])([fiu])$/.exec(type);
  if (m) return { scalar: { f: 'f32', i: 'i32', u: 'u32' }[m[2]], count: Number(m[1]) };
  if (/^(f32|i32|u32)$/.test(type)) return { scalar: type, count: 1 };
  throw new Error(`crt-webgpu: unsupported uniform member type '${type}'`);
}

const STAGES = () => ({ vertex: GPUShaderStage.VERTEX, fragment: GPUShaderStage.FRAGMENT, compute: GPUShaderStage.COMPUTE });
const ADDRESS = { clamp_to_edge: 'clamp-to-edge', repeat: 'repeat', mirrored_repeat: 'mirror-repeat' };

// Formats that can only be sampled without filtering (unless the device enabled float32-filterable).
const isFloat32 = (format) => /^(r|rg|rgba)32float$/.test(format);

// A small id per GPU object, to key cached bind groups by the textures they hold.
const objectIds = new WeakMap();
let nextObjectId = 1;
function idOf(object) {
  if (!objectIds.has(object)) objectIds.set(object, nextObjectId++);
  return objectIds.get(object);
}

// One pass of a preset: its pipeline, uniform buffer, samplers and params.
export function createCrtPass(device, { wgsl, preset: pass, format }) {
  if (!device) throw new Error('crt-webgpu: a GPUDevice is required');
  if (typeof wgsl !== 'string' || !wgsl) throw new Error('crt-webgpu: `wgsl` must be the shader source text');
  if (!format) throw new Error('crt-webgpu: `format` (the target texture format) is required');
  const target = wgslTarget(pass);
  // How each texture binding is sampled: the manifest's textures (the main input is "source").
  const sampling = new Map((pass.textures ?? []).map((t) => [t.name, t]));
  const textureEntries = target.bindGroupLayout.entries.filter((e) => e.texture);
  // clamp_to_border, which WebGPU lacks: crtforge's WGSL fades these textures' samples to the
  // transparent black border itself (their sampler entries say borderInShader); they clamp to the edge.
  const borderInShader = new Set(target.bindGroupLayout.entries.filter((e) => e.sampler?.borderInShader).map((e) => e.pairedTexture));
  const linear = (name) => (sampling.get(name)?.filter ?? 'linear') === 'linear';

  // ---- params: every non-builtin member of the uniform block ----
  const params = new Map();  // name -> { range, step, default, doc, unit, type, value }
  for (const m of pass.uniformBlock?.members ?? []) {
    if (m.builtin) continue;
    params.set(m.name, {
      name: m.name, type: m.type, range: m.range ?? null, step: m.step ?? null,
      default: m.default, unit: m.unit ?? '', doc: m.doc ?? '', value: m.default,
    });
  }

  // ---- uniform buffer: byte layout from targets.wgsl.uniformBuffer ----
  const layout = target.uniformBuffer;  // null when the shader has no uniforms (e.g. passthrough)
  const bufferEntry = target.bindGroupLayout.entries.find((e) => e.buffer);
  let uniformBytes = null, uniformBuffer = null;
  if (layout) {
    const size = Math.ceil(Math.max(layout.size, bufferEntry?.buffer?.minBindingSize ?? 0, 16) / 16) * 16;
    uniformBytes = new ArrayBuffer(size);
    uniformBuffer = device.createBuffer({ label: `crt ${layout.struct}`, size, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  }

  const module = device.createShaderModule({ label: `crt ${pass.alias ?? 'pass'}`, code: wgsl });
  const pipelines = new Map();   // which textures are unfilterable -> { pipeline, bindGroupLayout }
  const bindGroups = new Map();  // textures' ids -> GPUBindGroup
  const samplers = new Map();

  // The explicit bind group layout of the manifest. A linear texture fed an unfilterable format
  // is an error; a nearest one is declared unfilterable-float / non-filtering (exact texel reads,
  // same shader) — the manifest already declares nearest textures that way.
  function pipelineFor(unfilterable) {
    const key = [...unfilterable].sort().join(',');
    if (pipelines.has(key)) return pipelines.get(key);
    const stages = STAGES();
    const entries = target.bindGroupLayout.entries.map((e) => {
      const entry = { binding: e.binding, visibility: e.visibility.reduce((bits, s) => bits | stages[s], 0) };
      if (e.buffer) entry.buffer = { type: e.buffer.type, minBindingSize: e.buffer.minBindingSize ?? 0 };
      if (e.texture) entry.texture = { ...e.texture, ...(unfilterable.has(e.name) ? { sampleType: 'unfilterable-float' } : {}) };
      if (e.sampler) entry.sampler = { type: unfilterable.has(e.pairedTexture) ? 'non-filtering' : e.sampler.type };
      return entry;
    });
    const bindGroupLayout = device.createBindGroupLayout({ label: 'crt group 0', entries });
    const pipeline = device.createRenderPipeline({
      label: `crt pipeline ${pass.alias ?? ''}`,
      layout: device.createPipelineLayout({ bindGroupLayouts: [bindGroupLayout] }),
      vertex: { module, entryPoint: target.entryPoints.vertex },  // full-screen triangle, no buffers
      fragment: { module, entryPoint: target.entryPoints.fragment, targets: [{ format }] },
      primitive: { topology: 'triangle-list' },
    });
    const made = { pipeline, bindGroupLayout };
    pipelines.set(key, made);
    return made;
  }

  function samplerFor(textureName, unfilterable) {
    const t = sampling.get(textureName) ?? {};
    const filter = unfilterable || t.filter === 'nearest' ? 'nearest' : 'linear';
    const wrap = t.wrap ?? 'clamp_to_edge';
    const address = wrap === 'clamp_to_border' && borderInShader.has(textureName) ? 'clamp-to-edge' : ADDRESS[wrap];
    if (!address) throw new Error(`crt-webgpu: texture '${textureName}' wraps '${t.wrap}', which WebGPU has no address mode for`);
    // A mip chain's levels blend as the manifest's mipFilter says (default: as the filter); the
    // manifest declares such a sampler filtering, as WebGPU counts a blend of levels.
    const mipmapFilter = t.mipmap && !unfilterable ? t.mipFilter ?? filter : 'nearest';
    const key = `${filter}/${address}/${mipmapFilter}`;
    if (!samplers.has(key))
      samplers.set(key, device.createSampler({ magFilter: filter, minFilter: filter, mipmapFilter, addressModeU: address, addressModeV: address }));
    return samplers.get(key);
  }

  // What `time` the shader gets (the manifest's uniformBlock time member, reduceBy): the seconds
  // reduced by one period of the pass's angular speed S, in double precision, so the shader's phase
  // time * S is exact at any hour (an f32 of raw seconds loses it within a day).
  const reduceBy = pass.uniformBlock?.members?.find((m) => m.name === 'time')?.reduceBy;
  function shaderTime(seconds) {
    const speed = Math.abs(typeof reduceBy === 'number' ? reduceBy : params.get(reduceBy)?.value);
    if (!Number.isFinite(speed) || speed === 0) return seconds;
    const TAU = 2 * Math.PI;
    let phase = (seconds * speed) % TAU;
    if (phase < 0) phase += TAU;
    return phase / speed;
  }

  // Serialises builtins and params into uniformBytes (little-endian f32 / i32 / u32).
  function fillUniforms(builtins) {
    const view = new DataView(uniformBytes);
    for (const m of layout.members) {
      const { scalar, count } = parseType(m.type);
      const value = m.name in builtins ? builtins[m.name] : params.get(m.name)?.value;
      if (value === undefined) throw new Error(`crt-webgpu: no value for uniform member '${m.name}'`);
      const values = Array.isArray(value) ? [...value] : [value];
      if (count === 4 && values.length === 3) values.push(1);  // a colour in a vec4: alpha 1
      for (let i = 0; i < count; ++i) {
        const v = values[i] ?? 0, at = m.offset + 4 * i;
        if (scalar === 'f32') view.setFloat32(at, v, true);
        else if (scalar === 'i32') view.setInt32(at, Math.round(v), true);
        else view.setUint32(at, Math.round(v), true);
      }
    }
  }

  return {
    alias: pass.alias,
    // The names of the textures the shader reads: "source" (the main input) and the others.
    textures: textureEntries.map((e) => e.name),

    // The runtime params: [{ name, type, range, step, default, unit, doc, value }].
    params() {
      return [...params.values()].map((p) => ({ ...p, range: p.range && [...p.range], default: structuredClone(p.default) }));
    },

    hasParam(name) {
      return params.has(name);
    },

    // Sets one param. Numbers must lie in the manifest's range (ints must be whole); colours are
    // [r, g, b] with each channel in 0..1. Throws an Error naming the problem otherwise.
    setParam(name, value) {
      const p = params.get(name);
      if (!p) throw new Error(`crt-webgpu: unknown param '${name}' (this pass has: ${[...params.keys()].join(', ') || 'none'})`);
      if (Array.isArray(p.default)) {
        if (!Array.isArray(value) || value.length !== p.default.length || !value.every((c) => Number.isFinite(c) && c >= 0 && c <= 1))
          throw new Error(`crt-webgpu: param '${name}' is a colour: expected [r, g, b] with each channel in 0..1, got ${JSON.stringify(value)}`);
        p.value = [...value];
        return;
      }
      if (typeof value !== 'number' || !Number.isFinite(value))
        throw new Error(`crt-webgpu: param '${name}' needs a finite number, got ${JSON.stringify(value)}`);
      if (p.type === 'int' && !Number.isInteger(value)) throw new Error(`crt-webgpu: param '${name}' is an int, got ${value}`);
      if (p.range && (value < p.range[0] || value > p.range[1]))
        throw new Error(`crt-webgpu: param '${name}' = ${value} is outside its range ${p.range[0]}..${p.range[1]}`);
      p.value = value;
    },

    // Records the pass: `source` (GPUTexture, the main input) and `textures` ({ name: GPUTexture }
    // for the others) -> `target` (GPUTextureView of `format`). `width` x `height` is the size drawn
    // (the whole target, or `viewport` = { x, y, width, height } inside it, cleared to black
    // around it); `time` in seconds; `frameCount` the frame number (already reduced by the pass's
    // frameCountMod); `viewportSize` the screen's [width, height] the scene's last pass draws
    // (default: the size drawn).
    encode(encoder, { source, textures = {}, target: view, width, height, viewport = null, time = 0, frameCount = 0, viewportSize }) {
      if (!source || !view) throw new Error('crt-webgpu: encode needs `source` (GPUTexture: the main input, read or not) and `target` (GPUTextureView)');
      if (!(width > 0 && height > 0)) throw new Error('crt-webgpu: encode needs the drawn `width` and `height` in pixels');
      const bound = { ...textures, source };
      const unfilterable = new Set();
      for (const e of textureEntries) {
        const texture = bound[e.name];
        if (!texture) throw new Error(`crt-webgpu: pass ${pass.alias ?? ''} reads texture '${e.name}', which encode was not given`);
        if (isFloat32(texture.format) && !device.features.has('float32-filterable')) {
          if (linear(e.name))
            throw new Error(`crt-webgpu: texture '${e.name}' is filtered linearly; ${texture.format} is not filterable on this device (use rgba16float or rgba8unorm)`);
          unfilterable.add(e.name);
        }
      }
      const { pipeline, bindGroupLayout } = pipelineFor(unfilterable);

      if (layout) {
        fillUniforms({ outputSize: [width, height], sourceSize: [source.width, source.height], time: shaderTime(time), frameCount,
                       viewportSize: viewportSize ?? [width, height] });
        device.queue.writeBuffer(uniformBuffer, 0, uniformBytes);
      }

      const key = [...unfilterable].sort().join(',') + '|' + textureEntries.map((e) => idOf(bound[e.name])).join(',');
      let bindGroup = bindGroups.get(key);
      if (!bindGroup) {
        bindGroup = device.createBindGroup({
          label: `crt group 0 ${pass.alias ?? ''}`,
          layout: bindGroupLayout,
          entries: target.bindGroupLayout.entries.map((e) => ({
            binding: e.binding,
            resource: e.buffer ? { buffer: uniformBuffer }
              : e.texture ? bound[e.name].createView()
              : samplerFor(e.pairedTexture, unfilterable.has(e.pairedTexture)),
          })),
        });
        bindGroups.set(key, bindGroup);
      }

      const renderPass = encoder.beginRenderPass({
        label: `crt pass ${pass.alias ?? ''}`,
        colorAttachments: [{ view, loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: viewport ? 1 : 0 } }],
      });
      renderPass.setPipeline(pipeline);
      renderPass.setBindGroup(0, bindGroup);
      if (viewport) {
        renderPass.setViewport(viewport.x, viewport.y, viewport.width, viewport.height, 0, 1);
        renderPass.setScissorRect(viewport.x, viewport.y, viewport.width, viewport.height);
      }
      renderPass.draw(3);  // the vertex shader makes a full-screen triangle from vertex_index
      renderPass.end();
    },

    // The WGSL compiler's messages: [{ type: 'error' | 'warning' | 'info', lineNum, linePos, message }].
    async compilationInfo() {
      const info = await module.getCompilationInfo();
      return info.messages.map(({ type, lineNum, linePos, message }) => ({ type, lineNum, linePos, message }));
    },

    // Frees the GPU objects this pass made (not the textures it was given).
    destroy() {
      uniformBuffer?.destroy();
      bindGroups.clear();
    },
  };
}

// ---- scene geometry: the same rules as crtforge's scene model (generator/scene.cpp) ----

function sceneAspect(scene, source) {
  const aspect = scene.display?.aspect;
  if (aspect) return aspect[0] / aspect[1];
  const [px, py] = scene.source?.pixelAspect ?? [1, 1];
  return (source.width * px) / (source.height * py);
}

const clamp = (v, lo, hi) => Math.min(Math.max(v, lo), hi);
// C's lround: halves away from zero (Math.round takes -2.5 to -2).
const lround = (v) => Math.sign(v) * Math.round(Math.abs(v));

function centred(display, width, height) {
  width = clamp(width, 1, display.width);
  height = clamp(height, 1, display.height);
  return { x: Math.trunc((display.width - width) / 2), y: Math.trunc((display.height - height) / 2), width, height };
}

// The screen's rectangle in the display for `fit` (stretch | aspect | integer; default: the preset's).
export function screenRect(scene, display, source, fit = scene.display?.fit ?? 'stretch') {
  if (fit === 'stretch' || !(source.width > 0 && source.height > 0)) return { x: 0, y: 0, width: display.width, height: display.height };
  const aspect = sceneAspect(scene, source);
  if (fit === 'integer') {
    for (let k = Math.trunc(display.height / source.height); k >= 1; --k) {
      const height = k * source.height, width = lround(height * aspect);
      if (width <= display.width) return centred(display, width, height);
    }
  }
  if (display.width >= display.height * aspect) return centred(display, lround(display.height * aspect), display.height);
  return centred(display, display.width, lround(display.width / aspect));
}

// A texture source as the manifest writes it: original, original@N, <alias>, <alias>@previous, lut:<name>.
function parseFrom(from) {
  if (from === 'original') return { kind: 'original', back: 0 };
  let m = /^original@(\d+)$/.exec(from);
  if (m) return { kind: 'original', back: Number(m[1]) };
  m = /^lut:(.+)$/.exec(from);
  if (m) return { kind: 'lut', name: m[1] };
  m = /^(\w+)@previous$/.exec(from);
  if (m) return { kind: 'feedback', name: m[1] };
  return { kind: 'pass', name: from };
}

// What feeds a pass's main input ("source"), read by its shader or not.
const mainInput = (pass) => pass.input ?? pass.textures.find((t) => t.name === 'source')?.from ?? 'original';

// Every pass's output size: a factor of its main input (source), of the screen (viewport), or
// absolute pixels; the last pass's is the screen's.
export function passSizes(passes, source, screen) {
  const sizes = new Map();
  const out = passes.map((pass) => {
    const from = parseFrom(mainInput(pass));
    const input = (from.kind === 'pass' || from.kind === 'feedback') && sizes.has(from.name) ? sizes.get(from.name) : source;
    const axis = (s, inputExtent, screenExtent) => {
      const base = s.type === 'source' ? inputExtent : s.type === 'viewport' ? screenExtent : 1;
      return clamp(lround(base * s.factor), 1, 16384);
    };
    const size = { width: axis(pass.scale.x, input.width, screen.width), height: axis(pass.scale.y, input.height, screen.height) };
    sizes.set(pass.alias, size);
    return size;
  });
  out[out.length - 1] = { width: Math.max(screen.width, 1), height: Math.max(screen.height, 1) };
  return out;
}

// The manifest's pass formats as WebGPU texture formats (rgba32float is filterable only where the
// device enabled float32-filterable; the others always are).
const PASS_FORMAT = {
  rgba8: 'rgba8unorm', rgba8_srgb: 'rgba8unorm-srgb', rgba16f: 'rgba16float', rgba32f: 'rgba32float',
  rgb10a2: 'rgb10a2unorm', r16f: 'r16float', rg16f: 'rg16float',
};
function passFormat(pass) {
  const name = pass.format ?? 'rgba8';
  const format = Object.hasOwn(PASS_FORMAT, name) ? PASS_FORMAT[name] : undefined;
  if (!format) throw new Error(`crt-webgpu: pass '${pass.alias}' has format '${pass.format}', not one of ${Object.keys(PASS_FORMAT).join(', ')}`);
  return format;
}

// ---- mip chains, as RetroArch makes them: each level a linear blit of the one above ----

// floor(log2(max(width, height))) + 1 levels, level i max(1, size >> i).
export function mipLevelCount(width, height) {
  let levels = 1;
  for (let size = Math.max(width, height); size > 1; size >>= 1) ++levels;
  return levels;
}

// Level i drawn from level i - 1: each texel the linearly filtered sample of the level above at
// the texel's centre, which is what a linear vkCmdBlitImage of the whole level does.
const MIP_WGSL = `
@group(0) @binding(0) var above: texture_2d<f32>;
@group(0) @binding(1) var linearly: sampler;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
  let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
  return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
  let size = max(textureDimensions(above) / 2u, vec2<u32>(1u));
  return textureSampleLevel(above, linearly, at.xy / vec2<f32>(size), 0.0);
}`;
const mipMakers = new WeakMap();  // GPUDevice -> Map(format -> { pipeline, sampler })

// Records the levels 1.. of `texture` (made with mipLevelCount levels and RENDER_ATTACHMENT usage)
// from its level 0. A texture of one level records nothing.
export function encodeMipmaps(device, encoder, texture) {
  if (texture.mipLevelCount < 2) return;
  if (!mipMakers.has(device)) mipMakers.set(device, new Map());
  const makers = mipMakers.get(device);
  if (!makers.has(texture.format)) {
    const module = device.createShaderModule({ label: 'crt mip chain', code: MIP_WGSL });
    makers.set(texture.format, {
      pipeline: device.createRenderPipeline({
        label: `crt mip chain ${texture.format}`, layout: 'auto',
        vertex: { module, entryPoint: 'vs' }, fragment: { module, entryPoint: 'fs', targets: [{ format: texture.format }] },
      }),
      sampler: device.createSampler({ magFilter: 'linear', minFilter: 'linear' }),
    });
  }
  const { pipeline, sampler } = makers.get(texture.format);
  for (let level = 1; level < texture.mipLevelCount; ++level) {
    const bindGroup = device.createBindGroup({
      layout: pipeline.getBindGroupLayout(0),
      entries: [{ binding: 0, resource: texture.createView({ baseMipLevel: level - 1, mipLevelCount: 1 }) }, { binding: 1, resource: sampler }],
    });
    const pass = encoder.beginRenderPass({
      colorAttachments: [{ view: texture.createView({ baseMipLevel: level, mipLevelCount: 1 }), loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: 0 } }],
    });
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, bindGroup);
    pass.draw(3);
    pass.end();
  }
}

// The original's history is kept by drawing each frame's source into a texture of its own.
const COPY_WGSL = `
@group(0) @binding(0) var picture: texture_2d<f32>;
@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
  let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
  return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
@fragment fn fs(@builtin(position) at: vec4<f32>) -> @location(0) vec4<f32> {
  return textureLoad(picture, vec2<i32>(at.xy), 0);
}`;

// A whole preset: every pass in order, each into a texture of its size (the last into `target`
// at the screen's rectangle), with feedback textures swapped every frame and the original's
// history kept as the manifest's scene asks.
export function createCrtScene(device, { preset, wgsl, luts = {}, format }) {
  if (!preset?.passes?.length) throw new Error('crt-webgpu: `preset` must be a preset entry of manifest.json (with passes)');
  if (!format) throw new Error('crt-webgpu: `format` (the target texture format) is required');
  const scene = preset.scene ?? {};
  const passes = preset.passes;
  const shaderOf = (pass) => {
    const text = wgsl?.[pass.alias];
    if (typeof text !== 'string') throw new Error(`crt-webgpu: no WGSL for pass '${pass.alias}' (wgsl must map each pass alias to its shader text)`);
    return text;
  };
  // rgba32float can be filtered only where the device enabled float32-filterable: elsewhere a pass
  // output that some reader filters (linearly, blending mip levels, or through a chain made by
  // linear blits) is kept in rgba16float, the widest format such a device filters.
  const filtered = new Set(passes.flatMap((p) => p.textures.filter((t) => (t.filter ?? 'linear') === 'linear' || t.mipmap)
    .map((t) => parseFrom(t.from)).filter((f) => f.kind === 'pass' || f.kind === 'feedback').map((f) => f.name)));
  const storedFormat = (pass) => {
    const f = passFormat(pass);
    return isFloat32(f) && filtered.has(pass.alias) && !device.features.has('float32-filterable') ? 'rgba16float' : f;
  };
  // Each pass draws into a texture of its own format; the last one draws into the target (and,
  // when a later frame reads it back, into a texture too).
  const runners = passes.map((pass) => createCrtPass(device, { wgsl: shaderOf(pass), preset: pass, format: storedFormat(pass) }));
  const display = createCrtPass(device, { wgsl: shaderOf(passes[passes.length - 1]), preset: passes[passes.length - 1], format });
  const everyRunner = [...runners, display];
  for (const pass of passes)
    for (const t of pass.textures) {
      const from = parseFrom(t.from);
      if (from.kind === 'lut' && !luts[from.name]) throw new Error(`crt-webgpu: pass ${pass.alias} reads LUT '${from.name}': pass its GPUTexture in luts`);
    }
  const feedback = new Set(passes.flatMap((p) => p.textures.map((t) => parseFrom(t.from)).filter((f) => f.kind === 'feedback').map((f) => f.name)));
  // What some reader samples through a mip chain: those pass outputs (and their feedback copies)
  // get one, filled after the pass draws; the original is copied into one each frame; a LUT must
  // come with one (createLutTexture's mipmap option).
  const mipmapped = mipmappedSources(preset);
  const mipOutputs = new Set(mipmapped.filter((f) => f.kind === 'pass' || f.kind === 'feedback').map((f) => f.name));
  const mipOriginal = mipmapped.some((f) => f.kind === 'original');
  if (mipmapped.some((f) => f.kind === 'original' && f.back > 0))
    throw new Error('crt-webgpu: a pass reads an earlier original (original@N) through a mip chain, which this driver does not make');
  for (const f of mipmapped)
    if (f.kind === 'lut' && luts[f.name].mipLevelCount < 2)
      throw new Error(`crt-webgpu: LUT '${f.name}' is read through a mip chain: pass a GPUTexture that has one (createLutTexture(device, bytes, name, { mipmap: true }))`);
  const lastAlias = passes[passes.length - 1].alias;
  const historyFrames = scene.historyFrames ?? 0;

  let outputs = new Map();    // alias -> GPUTexture of this frame
  let previous = new Map();   // alias -> GPUTexture of the previous frame (feedback passes)
  let history = [];           // the originals of 1, 2, ... frames ago
  let sizeKey = '';
  let copy = null;            // the history copy pipeline, made on first use
  let frameCounter = 0;
  let original = null;        // the source with a mip chain (mipOriginal)

  const usage = () => GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_SRC;
  const texture = (label, size, fmt, mip = false) => device.createTexture({
    label, size: [size.width, size.height], format: fmt, usage: usage(), mipLevelCount: mip ? mipLevelCount(size.width, size.height) : 1,
  });

  function destroyTextures() {
    for (const t of [...outputs.values(), ...previous.values(), ...history, ...(original ? [original] : [])]) t.destroy();
    outputs = new Map();
    previous = new Map();
    history = [];
    original = null;
  }

  // (Re)makes the pass textures when the sizes change; new textures read as zero (transparent
  // black), which is what the first frame's feedback and history are.
  function prepare(sizes, source) {
    const key = JSON.stringify(sizes) + `|${source.width}x${source.height}`;
    if (key === sizeKey) return;
    destroyTextures();
    sizeKey = key;
    passes.forEach((pass, i) => {
      const fmt = storedFormat(pass);
      const mip = mipOutputs.has(pass.alias);
      if (pass.alias !== lastAlias || feedback.has(pass.alias)) outputs.set(pass.alias, texture(`crt ${pass.alias}`, sizes[i], fmt, mip));
      if (feedback.has(pass.alias)) previous.set(pass.alias, texture(`crt ${pass.alias}@previous`, sizes[i], fmt, mip));
    });
    for (let n = 0; n < historyFrames; ++n) history.push(texture(`crt original@${n + 1}`, source, 'rgba16float'));
    if (mipOriginal) original = texture('crt original (mip chain)', source, 'rgba16float', true);
  }

  function copyInto(encoder, from, to) {
    if (!copy) {
      const module = device.createShaderModule({ label: 'crt history copy', code: COPY_WGSL });
      copy = device.createRenderPipeline({
        label: 'crt history copy', layout: 'auto',
        vertex: { module, entryPoint: 'vs' }, fragment: { module, entryPoint: 'fs', targets: [{ format: 'rgba16float' }] },
      });
    }
    const bindGroup = device.createBindGroup({ layout: copy.getBindGroupLayout(0), entries: [{ binding: 0, resource: from.createView() }] });
    const pass = encoder.beginRenderPass({ colorAttachments: [{ view: to.createView({ mipLevelCount: 1 }), loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: 0 } }] });
    pass.setPipeline(copy);
    pass.setBindGroup(0, bindGroup);
    pass.draw(3);
    pass.end();
  }

  return {
    passes: runners,

    // The runtime params of every pass: [{ pass, name, ... }].
    params() {
      return runners.flatMap((r) => r.params().map((p) => ({ pass: r.alias, ...p })));
    },

    // Sets a param on every pass that has it (throws when none has).
    setParam(name, value) {
      const owners = everyRunner.filter((r) => r.hasParam(name));
      if (!owners.length) throw new Error(`crt-webgpu: no pass of this preset has a param '${name}'`);
      for (const r of owners) r.setParam(name, value);
    },

    // The screen's rectangle in a display of width x height for this source.
    screenRect(width, height, source, fit) {
      return screenRect(scene, { width, height }, source, fit);
    },

    // Records one frame: `source` (GPUTexture) -> `target` (GPUTextureView of `format`, `width` x
    // `height` pixels: the screen's rectangle over black, per the preset's display fit or `fit`).
    // `frame` defaults to a counter advanced by every call; `time` defaults to frame / fps.
    encode(encoder, { source, target, width, height, frame = frameCounter, time, fit }) {
      if (!source || !target) throw new Error('crt-webgpu: encode needs `source` (GPUTexture) and `target` (GPUTextureView)');
      if (!(width > 0 && height > 0)) throw new Error('crt-webgpu: encode needs the target `width` and `height` in pixels');
      frameCounter = frame + 1;
      const seconds = time ?? frame / (scene.fps ?? 60);
      const screen = screenRect(scene, { width, height }, source, fit);
      const sizes = passSizes(passes, source, screen);
      prepare(sizes, source);
      if (original) {
        copyInto(encoder, source, original);
        encodeMipmaps(device, encoder, original);
      }
      const resolve = (from, mip = false) => {
        switch (from.kind) {
          case 'original': return from.back === 0 ? (mip && original ? original : source) : history[from.back - 1];
          case 'pass': return outputs.get(from.name);
          case 'feedback': return previous.get(from.name);
          case 'lut': return luts[from.name];
        }
        return undefined;
      };
      passes.forEach((pass, i) => {
        const bound = {};
        for (const t of pass.textures) bound[t.name] = resolve(parseFrom(t.from), t.mipmap);
        const { source: read, ...textures } = bound;
        const main = read ?? resolve(parseFrom(mainInput(pass)));  // its size is sourceSize
        const frameCount = pass.frameCountMod > 0 ? frame % pass.frameCountMod : frame;
        const common = { source: main, textures, time: seconds, frameCount, viewportSize: [screen.width, screen.height] };
        if (outputs.has(pass.alias)) {
          const out = outputs.get(pass.alias);
          runners[i].encode(encoder, { ...common, target: out.createView({ mipLevelCount: 1 }), width: sizes[i].width, height: sizes[i].height });
          encodeMipmaps(device, encoder, out);
        }
        if (pass.alias === lastAlias) {
          const full = screen.width === width && screen.height === height;
          display.encode(encoder, { ...common, target, width: screen.width, height: screen.height, viewport: full ? null : screen });
        }
      });
      // This frame's outputs become the next frame's previous ones; the original joins the history.
      for (const alias of feedback) {
        const done = outputs.get(alias);
        outputs.set(alias, previous.get(alias));
        previous.set(alias, done);
      }
      if (history.length) {
        const oldest = history.pop();
        copyInto(encoder, source, oldest);
        history.unshift(oldest);
      }
    },

    destroy() {
      destroyTextures();
      for (const r of everyRunner) r.destroy();
    },
  };
}

// ---- LUTs: the PNGs of luts/ as textures, in a browser and in Node alike ----

// A PNG as RGBA8 texels, read with the platform's own DecompressionStream: no canvas, no colour
// management, bytes as stored. Every colour type (grey, RGB, palette, grey + alpha, RGBA), bit
// depth (1 to 16: a 16-bit sample keeps its high byte) and Adam7 interlacing: crtforge writes 8-bit
// RGB(A) LUTs, and an imported RetroArch preset ships the library's own PNGs as they are.
export async function decodePng(bytes, name = 'PNG') {
  const u8 = bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes);
  const be32 = (at) => ((u8[at] << 24) | (u8[at + 1] << 16) | (u8[at + 2] << 8) | u8[at + 3]) >>> 0;
  if (u8.length < 8 || be32(0) !== 0x89504e47) throw new Error(`crt-webgpu: ${name} is not a PNG file`);
  const CHANNELS = { 0: 1, 2: 3, 3: 1, 4: 2, 6: 4 };
  let width = 0, height = 0, depth = 0, colour = 0, interlace = 0, palette = null, transparency = null;
  const chunks = [];
  for (let at = 8; at + 8 <= u8.length;) {
    const length = be32(at), type = String.fromCharCode(...u8.subarray(at + 4, at + 8));
    const body = u8.subarray(at + 8, at + 8 + length);
    if (type === 'IHDR') {
      width = be32(at + 8);
      height = be32(at + 12);
      [depth, colour, interlace] = [body[8], body[9], body[12]];
      const depths = colour === 0 ? [1, 2, 4, 8, 16] : colour === 3 ? [1, 2, 4, 8] : [8, 16];
      if (!(colour in CHANNELS) || !depths.includes(depth) || interlace > 1)
        throw new Error(`crt-webgpu: ${name}: colour type ${colour} at ${depth} bits (interlace ${interlace}) is not a valid PNG`);
    } else if (type === 'PLTE') palette = body;
    else if (type === 'tRNS') transparency = body;
    else if (type === 'IDAT') chunks.push(body);
    else if (type === 'IEND') break;
    at += 12 + length;
  }
  if (!width || !height) throw new Error(`crt-webgpu: ${name} has no IHDR chunk`);
  if (colour === 3 && !palette) throw new Error(`crt-webgpu: ${name}: a palette PNG without its PLTE chunk`);
  const inflated = new Blob(chunks).stream().pipeThrough(new DecompressionStream('deflate'));
  const raw = new Uint8Array(await new Response(inflated).arrayBuffer());
  const channels = CHANNELS[colour];
  const bpp = Math.max(1, (channels * depth) >> 3);  // the filters' byte distance
  const maxSample = (1 << Math.min(depth, 8)) - 1;
  // Sample k of pixel x in an unfiltered row, scaled to 0..255 (a palette index as it is).
  const sample = (row, x, k) => {
    if (depth === 16) return row[(x * channels + k) * 2];
    if (depth === 8) return row[x * channels + k];
    const bit = (x * channels + k) * depth, v = (row[bit >> 3] >> (8 - depth - (bit & 7))) & maxSample;
    return colour === 3 ? v : Math.round((v * 255) / maxSample);
  };
  const out = new Uint8Array(width * height * 4);
  const put = (row, x, px, py) => {
    const o = (py * width + px) * 4;
    if (colour === 3) {
      const i = sample(row, x, 0);
      if (3 * i + 2 >= palette.length) throw new Error(`crt-webgpu: ${name}: palette index ${i} past its PLTE chunk`);
      out[o] = palette[3 * i];
      out[o + 1] = palette[3 * i + 1];
      out[o + 2] = palette[3 * i + 2];
      out[o + 3] = transparency && i < transparency.length ? transparency[i] : 255;
    } else if (channels >= 3) {
      out[o] = sample(row, x, 0);
      out[o + 1] = sample(row, x, 1);
      out[o + 2] = sample(row, x, 2);
      out[o + 3] = channels === 4 ? sample(row, x, 3) : 255;
    } else {
      out[o] = out[o + 1] = out[o + 2] = sample(row, x, 0);
      out[o + 3] = channels === 2 ? sample(row, x, 1) : 255;
    }
  };
  // Adam7: seven sub-images (x0, y0, dx, dy), each filtered on its own; or the whole image once.
  const passes = interlace ? [[0, 0, 8, 8], [4, 0, 8, 8], [0, 4, 4, 8], [2, 0, 4, 4], [0, 2, 2, 4], [1, 0, 2, 2], [0, 1, 1, 2]] : [[0, 0, 1, 1]];
  let at = 0;
  for (const [x0, y0, dx, dy] of passes) {
    const w = Math.ceil((width - x0) / dx), h = Math.ceil((height - y0) / dy);
    if (w <= 0 || h <= 0) continue;
    const stride = Math.ceil((w * channels * depth) / 8);
    if (raw.length < at + h * (stride + 1)) throw new Error(`crt-webgpu: ${name} holds fewer rows than its header says`);
    let prior = new Uint8Array(stride);
    for (let y = 0; y < h; ++y, at += stride + 1) {
      const filter = raw[at], line = raw.subarray(at + 1, at + 1 + stride);
      const row = new Uint8Array(stride);
      for (let i = 0; i < stride; ++i) {
        const a = i >= bpp ? row[i - bpp] : 0, b = prior[i], c = i >= bpp ? prior[i - bpp] : 0;
        let p = 0;
        if (filter === 1) p = a;
        else if (filter === 2) p = b;
        else if (filter === 3) p = (a + b) >> 1;
        else if (filter === 4) {
          const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c);
          p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
        }
        row[i] = (line[i] + p) & 0xff;
      }
      for (let x = 0; x < w; ++x) put(row, x, x0 + x * dx, y0 + y * dy);
      prior = row;
    }
  }
  return { width, height, data: out };
}

// What a preset (a manifest entry) reads through a mip chain: each reader's source, parsed.
function mipmappedSources(preset) {
  return preset.passes.flatMap((p) => p.textures.filter((t) => t.mipmap).map((t) => parseFrom(t.from)));
}

// The names of the LUTs a preset reads through a mip chain.
export function mipmappedLuts(preset) {
  return new Set(mipmappedSources(preset).filter((f) => f.kind === 'lut').map((f) => f.name));
}

// A LUT's PNG bytes as an rgba8unorm texture (texel bytes exactly as in the file); with
// `mipmap`, with its mip chain (a preset whose passes read the LUT with mipmap: true needs it).
export async function createLutTexture(device, bytes, name = 'LUT', { mipmap = false } = {}) {
  const image = await decodePng(bytes, name);
  const levels = mipmap ? mipLevelCount(image.width, image.height) : 1;
  const texture = device.createTexture({
    size: [image.width, image.height], format: 'rgba8unorm', mipLevelCount: levels,
    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | (levels > 1 ? GPUTextureUsage.RENDER_ATTACHMENT : 0),
  });
  device.queue.writeTexture({ texture }, image.data, { bytesPerRow: image.width * 4 }, [image.width, image.height]);
  if (levels > 1) {
    const encoder = device.createCommandEncoder({ label: `crt mip chain of ${name}` });
    encodeMipmaps(device, encoder, texture);
    device.queue.submit([encoder.finish()]);
  }
  return texture;
}
