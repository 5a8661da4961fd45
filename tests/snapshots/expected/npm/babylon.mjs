// crtforge-presets/babylon: a crtforge preset as a post-processing pass of a Babylon.js WebGPUEngine.
// It runs on the engine's own GPUDevice: the pass reads a texture your scene was drawn into (a
// RenderTargetTexture, or any Babylon texture) and writes a RenderTargetTexture.
//
//   import { createBabylonCrtPass } from 'crtforge-presets/babylon';
//   const engine = new WebGPUEngine(canvas); await engine.initAsync();
//   const crt = await createBabylonCrtPass(engine, 'classic');
//   const game = new RenderTargetTexture('game', { width: 256, height: 224 }, scene);   // your frame
//   const screen = new RenderTargetTexture('screen', { width: 1024, height: 768 }, scene);
//   scene.onAfterRenderObservable.add(() => crt.render(game, screen, { time: performance.now() / 1000 }));
//
// Not a Babylon PostProcess: a PostProcess is one fragment shader in Babylon's own binding layout,
// and a crtforge preset is a scene of passes with its own (feedback, lookup textures), so the pass
// runs on the engine's device between textures instead. Show `screen` as you would any texture
// (a fullscreen Layer, a material). The input should hold what you would show: in the display's
// encoding (see the package README).
import { loadCrtPreset } from './index.mjs';

export async function createBabylonCrtPass(engine, name, { format = 'rgba8unorm' } = {}) {
  // The WebGPUEngine's device: Babylon keeps it as _device (no public accessor in v9).
  const device = engine?._device;
  if (!device || typeof engine.flushFramebuffer !== 'function')
    throw new Error('crtforge-presets/babylon: needs a Babylon.js WebGPUEngine after `await engine.initAsync()`');
  // One scene per target format (a pipeline is made for one format); the params set so far are
  // replayed on a scene made later, so every format draws with the same values.
  const scenes = new Map();  // format -> Promise of its scene
  const values = new Map();  // param -> value
  const sceneFor = (targetFormat) => {
    if (!scenes.has(targetFormat)) {
      scenes.set(targetFormat, loadCrtPreset(device, name, { format: targetFormat }).then((scene) => {
        for (const [param, value] of values) scene.setParam(param, value);
        return scene;
      }));
    }
    return scenes.get(targetFormat);
  };
  const first = await sceneFor(format);

  // The GPUTexture behind a Babylon texture (BaseTexture or InternalTexture).
  const gpuTexture = (texture) => {
    const internal = typeof texture?.getInternalTexture === 'function' ? texture.getInternalTexture() : texture;
    const gpu = internal?._hardwareTexture?.underlyingResource;
    if (!gpu) throw new Error('crtforge-presets/babylon: Babylon has no GPU texture for this texture (not created yet, or not a WebGPU texture)');
    return gpu;
  };

  return {
    // The scene made for `format` (setParam below reaches every format's scene).
    scene: first,
    params: () => first.params(),
    setParam(param, value) {
      first.setParam(param, value);  // throws, naming the problem, for a bad name or value
      values.set(param, value);
      for (const scene of scenes.values()) scene.then((s) => s.setParam(param, value));
    },
    // Draws `input` through the preset into `output` (a RenderTargetTexture), at output's size.
    // Babylon's recorded work is submitted first (flushFramebuffer), so the input is drawn.
    async render(input, output, { frame, time, fit } = {}) {
      const target = gpuTexture(output);
      const scene = await sceneFor(target.format);
      const source = gpuTexture(input);
      engine.flushFramebuffer();
      const encoder = device.createCommandEncoder({ label: `crtforge ${name}` });
      scene.encode(encoder, { source, target: target.createView(), width: target.width, height: target.height, frame, time, fit });
      device.queue.submit([encoder.finish()]);
    },
    // Lower level: records the pass into your encoder, onto any view of `format`.
    encode(encoder, options) {
      first.encode(encoder, options);
    },
    // The GPUTexture behind a Babylon texture (for encode()'s `source`).
    textureOf: gpuTexture,
    destroy() {
      for (const scene of scenes.values()) scene.then((s) => s.destroy());
      scenes.clear();
    },
  };
}
