// crt-webgpu.mjs: run one crtforge CRT preset as a WebGPU post-process pass.
//
// Drop-in, dependency-free ES module. It works wherever WebGPU does: in a browser, or in Node with
// dawn.node (npm `webgpu`) once its `globals` are on globalThis. It reads GPUShaderStage,
// GPUBufferUsage and GPUTextureUsage from globalThis.
//
// Everything it needs comes from `crtforge export`:
//   wgsl   - the text of wgsl/<preset>.wgsl
//   preset - a pass of manifest.json's presets.<preset>.passes (uniform block, textures, targets.wgsl);
//            a single-pass preset has one
//
//   const pass = createCrtPass(device, { wgsl, preset, format: 'bgra8unorm' });
//   pass.setParam('scanlineIntensity', 0.7);
//   pass.encode(encoder, { source, target: view, width, height, time });
//
// encode() writes the uniform buffer with device.queue.writeBuffer, so the values in effect are
// the ones of the last encode() before the command buffer is submitted: encode one CRT pass per
// submit (or create one pass object per draw).

// The WGSL half of the manifest: bindings, entry points, uniform byte layout.
function wgslTarget(preset) {
  const target = preset?.targets?.wgsl;
  if (!target) throw new Error('crt-webgpu: the preset has no targets.wgsl entry (export with --target wgsl)');
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

// Formats that can only be sampled without filtering (unless the device enabled float32-filterable).
const isFloat32 = (format) => /^(r|rg|rgba)32float$/.test(format);

export function createCrtPass(device, { wgsl, preset, format }) {
  if (!device) throw new Error('crt-webgpu: a GPUDevice is required');
  if (typeof wgsl !== 'string' || !wgsl) throw new Error('crt-webgpu: `wgsl` must be the shader source text');
  if (!format) throw new Error('crt-webgpu: `format` (the target texture format) is required');
  const target = wgslTarget(preset);
  const filter = preset.textures?.[0]?.filter === 'nearest' ? 'nearest' : 'linear';

  // ---- params: every non-builtin member of the uniform block ----
  const blockMembers = preset.uniformBlock?.members ?? [];
  const params = new Map();  // name -> { range, step, default, doc, unit, type, value }
  for (const m of blockMembers) {
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

  const module = device.createShaderModule({ label: 'crt shader', code: wgsl });
  const pipelines = new Map();       // sampling kind -> { pipeline, bindGroupLayout }
  const bindGroups = new WeakMap();  // source GPUTexture -> GPUBindGroup
  const samplers = new Map();

  // The explicit bind group layout of the manifest. For a `nearest` preset fed an unfilterable
  // source (rgba32float without float32-filterable) the texture and sampler are declared
  // unfilterable-float / non-filtering instead: exact texel reads, same shader.
  function pipelineFor(unfilterable) {
    const key = unfilterable ? 'unfilterable' : 'filterable';
    if (pipelines.has(key)) return pipelines.get(key);
    const stages = STAGES();
    const entries = target.bindGroupLayout.entries.map((e) => {
      const entry = { binding: e.binding, visibility: e.visibility.reduce((bits, s) => bits | stages[s], 0) };
      if (e.buffer) entry.buffer = { type: e.buffer.type, minBindingSize: e.buffer.minBindingSize ?? 0 };
      if (e.texture) entry.texture = { ...e.texture, ...(unfilterable ? { sampleType: 'unfilterable-float' } : {}) };
      if (e.sampler) entry.sampler = { type: unfilterable ? 'non-filtering' : e.sampler.type };
      return entry;
    });
    const bindGroupLayout = device.createBindGroupLayout({ label: 'crt group 0', entries });
    const pipeline = device.createRenderPipeline({
      label: 'crt pipeline',
      layout: device.createPipelineLayout({ bindGroupLayouts: [bindGroupLayout] }),
      vertex: { module, entryPoint: target.entryPoints.vertex },  // full-screen triangle, no buffers
      fragment: { module, entryPoint: target.entryPoints.fragment, targets: [{ format }] },
      primitive: { topology: 'triangle-list' },
    });
    const made = { pipeline, bindGroupLayout };
    pipelines.set(key, made);
    return made;
  }

  function samplerFor(unfilterable) {
    const f = unfilterable ? 'nearest' : filter;
    if (!samplers.has(f))
      samplers.set(f, device.createSampler({ magFilter: f, minFilter: f, addressModeU: 'clamp-to-edge', addressModeV: 'clamp-to-edge' }));
    return samplers.get(f);
  }

  // Serialises builtins and params into uniformBytes (little-endian f32 / i32 / u32).
  function fillUniforms(builtins) {
    const view = new DataView(uniformBytes);
    for (const m of layout.members) {
      const { scalar, count } = parseType(m.type);
      let value = m.name in builtins ? builtins[m.name] : params.get(m.name)?.value;
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
    // The runtime params: [{ name, type, range, step, default, unit, doc, value }].
    params() {
      return [...params.values()].map((p) => ({ ...p, range: p.range && [...p.range], default: structuredClone(p.default) }));
    },

    // Sets one param. Numbers must lie in the manifest's range (ints must be whole); colours are
    // [r, g, b] with each channel in 0..1. Throws an Error naming the problem otherwise.
    setParam(name, value) {
      const p = params.get(name);
      if (!p) throw new Error(`crt-webgpu: unknown param '${name}' (this preset has: ${[...params.keys()].join(', ') || 'none'})`);
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

    // Records the CRT pass: `source` (GPUTexture) -> `target` (GPUTextureView of `format`),
    // `width` x `height` = the target's size in pixels, `time` in seconds.
    encode(encoder, { source, target: view, width, height, time = 0 }) {
      if (!source || !view) throw new Error('crt-webgpu: encode needs `source` (GPUTexture) and `target` (GPUTextureView)');
      if (!(width > 0 && height > 0)) throw new Error('crt-webgpu: encode needs the target `width` and `height` in pixels');
      const unfilterable = isFloat32(source.format) && !device.features.has('float32-filterable');
      if (unfilterable && filter === 'linear')
        throw new Error(`crt-webgpu: this preset filters its source linearly; ${source.format} is not filterable on this device (use rgba16float or rgba8unorm)`);
      const { pipeline, bindGroupLayout } = pipelineFor(unfilterable);

      if (layout) {
        fillUniforms({ outputSize: [width, height], sourceSize: [source.width, source.height], time });
        device.queue.writeBuffer(uniformBuffer, 0, uniformBytes);
      }

      let bindGroup = bindGroups.get(source);
      if (!bindGroup) {
        const resources = { buffer: uniformBuffer && { buffer: uniformBuffer }, texture: source.createView(), sampler: samplerFor(unfilterable) };
        bindGroup = device.createBindGroup({
          label: 'crt group 0',
          layout: bindGroupLayout,
          entries: target.bindGroupLayout.entries.map((e) => ({
            binding: e.binding,
            resource: e.buffer ? resources.buffer : e.texture ? resources.texture : resources.sampler,
          })),
        });
        bindGroups.set(source, bindGroup);
      }

      const pass = encoder.beginRenderPass({
        label: 'crt pass',
        colorAttachments: [{ view, loadOp: 'clear', storeOp: 'store', clearValue: { r: 0, g: 0, b: 0, a: 1 } }],
      });
      pass.setPipeline(pipeline);
      pass.setBindGroup(0, bindGroup);
      pass.draw(3);  // the vertex shader makes a full-screen triangle from vertex_index
      pass.end();
    },

    // The WGSL compiler's messages: [{ type: 'error' | 'warning' | 'info', lineNum, linePos, message }].
    async compilationInfo() {
      const info = await module.getCompilationInfo();
      return info.messages.map(({ type, lineNum, linePos, message }) => ({ type, lineNum, linePos, message }));
    },

    // Frees the GPU objects this pass made (not `source` or `target`).
    destroy() {
      uniformBuffer?.destroy();
    },
  };
}
