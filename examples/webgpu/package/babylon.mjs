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
import { createFrameworkPass } from './framework-pass.mjs';

export async function createBabylonCrtPass(engine, name, { format = 'rgba8unorm' } = {}) {
  // The WebGPUEngine's device: Babylon keeps it as _device (no public accessor in v9).
  const device = engine?._device;
  if (!device || typeof engine.flushFramebuffer !== 'function')
    throw new Error('crtforge-presets/babylon: needs a Babylon.js WebGPUEngine after `await engine.initAsync()`');
  // The GPUTexture behind a Babylon texture (BaseTexture or InternalTexture).
  const textureOf = (texture) => {
    const internal = typeof texture?.getInternalTexture === 'function' ? texture.getInternalTexture() : texture;
    const gpu = internal?._hardwareTexture?.underlyingResource;
    if (!gpu) throw new Error('crtforge-presets/babylon: Babylon has no GPU texture for this texture (not created yet, or not a WebGPU texture)');
    return gpu;
  };
  // Babylon records into its own encoders until the frame ends: submit them first, so the input
  // holds what was drawn into it.
  return createFrameworkPass(device, name, { format, textureOf, beforeSubmit: () => engine.flushFramebuffer() });
}
