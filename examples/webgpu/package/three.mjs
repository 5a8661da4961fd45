// crtforge-presets/three: a crtforge preset as a post-processing pass of three.js's
// WebGPURenderer. It runs on the renderer's own GPUDevice: the pass reads a RenderTarget your
// scene was drawn into and writes another (or any GPUTextureView, such as the canvas's).
//
//   import { createThreeCrtPass } from 'crtforge-presets/three';
//   await renderer.init();
//   const crt = await createThreeCrtPass(renderer, 'classic');
//   renderer.setRenderTarget(game); renderer.render(scene, camera);   // your frame, display-referred
//   crt.render(game, screen, { time: clock.elapsedTime });            // screen: a RenderTarget
//
// The input should hold what you would show: tone mapped and in the display's encoding (see the
// package README: the pass goes after tone mapping). Output and input are RenderTargets whose
// textures three has created (the pass creates the output's by clearing it once if needed).
import { loadCrtPreset } from './index.mjs';

export async function createThreeCrtPass(renderer, name, { format = 'rgba8unorm' } = {}) {
  const device = renderer?.backend?.device;
  if (!device) throw new Error('crtforge-presets/three: needs a WebGPURenderer after `await renderer.init()` (the WebGPU backend)');
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

  // The GPUTexture three made for a RenderTarget's texture, made now (by a clear) if three has not yet.
  const gpuTexture = (renderTarget) => {
    let texture = renderer.backend.get(renderTarget.texture)?.texture;
    if (!texture) {
      const previous = renderer.getRenderTarget();
      renderer.setRenderTarget(renderTarget);
      renderer.clear();
      renderer.setRenderTarget(previous);
      texture = renderer.backend.get(renderTarget.texture)?.texture;
    }
    if (!texture) throw new Error('crtforge-presets/three: three has no GPU texture for this RenderTarget');
    return texture;
  };

  const pass = {
    // The scene made for `format` (setParam below reaches every format's scene).
    scene: first,
    params: () => first.params(),
    setParam(param, value) {
      first.setParam(param, value);  // throws, naming the problem, for a bad name or value
      values.set(param, value);
      for (const scene of scenes.values()) scene.then((s) => s.setParam(param, value));
    },
    // Draws `input` (RenderTarget) through the preset into `output` (RenderTarget), at output's size.
    async render(input, output, { frame, time, fit } = {}) {
      const target = gpuTexture(output);
      const scene = await sceneFor(target.format);
      const encoder = device.createCommandEncoder({ label: `crtforge ${name}` });
      scene.encode(encoder, { source: gpuTexture(input), target: target.createView(), width: target.width, height: target.height, frame, time, fit });
      device.queue.submit([encoder.finish()]);
    },
    // Lower level: records the pass into your encoder, onto any view of `format`.
    encode(encoder, options) {
      first.encode(encoder, options);
    },
    // The GPUTexture behind a RenderTarget (for encode()'s `source`).
    textureOf: gpuTexture,
    destroy() {
      for (const scene of scenes.values()) scene.then((s) => s.destroy());
      scenes.clear();
    },
  };
  return pass;
}
