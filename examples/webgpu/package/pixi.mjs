// crtforge-presets/pixi: a crtforge preset as a post-processing pass of a PixiJS v8 WebGPURenderer.
// It runs on the renderer's own GPUDevice between two RenderTextures: draw your stage into one,
// the pass renders the CRT picture into the other, show that with a Sprite.
//
//   import { createPixiCrtPass } from 'crtforge-presets/pixi';
//   await app.init({ preference: 'webgpu' });                     // app.renderer: a WebGPURenderer
//   const crt = await createPixiCrtPass(app.renderer, 'classic');
//   const game = RenderTexture.create({ width: 256, height: 224 });
//   const screen = RenderTexture.create({ width: 1024, height: 768 });
//   app.stage.addChild(new Sprite(screen));
//   app.ticker.add((ticker) => {
//     app.renderer.render({ container: gameStage, target: game });  // your frame, display-referred
//     crt.render(game, screen, { time: ticker.lastTime / 1000 });
//   });
//
// Not a PixiJS Filter: a Filter's shader must use Pixi's bind group 0 (its global filter uniforms at
// binding 0, the input at 1), and a crtforge preset is a whole scene of passes with its own layout
// (feedback, lookup textures), so the pass runs on Pixi's device instead, as a Filter would.
// The input should hold what you would show: in the display's encoding (see the package README).
import { loadCrtPreset } from './index.mjs';

export async function createPixiCrtPass(renderer, name, { format = 'bgra8unorm' } = {}) {
  const device = renderer?.gpu?.device;
  if (!device || typeof renderer?.texture?.getGpuSource !== 'function')
    throw new Error('crtforge-presets/pixi: needs a PixiJS v8 WebGPURenderer after `await renderer.init()` (preference: "webgpu")');
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

  // The GPUTexture behind a Pixi Texture (a RenderTexture), made now if Pixi has not yet.
  const gpuTexture = (texture) => {
    const source = texture?.source ?? texture;
    const gpu = source ? renderer.texture.getGpuSource(source) : null;
    if (!gpu) throw new Error('crtforge-presets/pixi: Pixi has no GPU texture for this texture');
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
    // Draws `input` (a RenderTexture Pixi has drawn) through the preset into `output` (a
    // RenderTexture), at output's size. Submitted after Pixi's own work on the same queue.
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
    // The GPUTexture behind a Pixi texture (for encode()'s `source`).
    textureOf: gpuTexture,
    destroy() {
      for (const scene of scenes.values()) scene.then((s) => s.destroy());
      scenes.clear();
    },
  };
}
