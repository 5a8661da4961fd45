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
import { createFrameworkPass } from './framework-pass.mjs';

export async function createPixiCrtPass(renderer, name, { format = 'bgra8unorm' } = {}) {
  const device = renderer?.gpu?.device;
  if (!device || typeof renderer?.texture?.getGpuSource !== 'function')
    throw new Error('crtforge-presets/pixi: needs a PixiJS v8 WebGPURenderer after `await renderer.init()` (preference: "webgpu")');
  // The GPUTexture behind a Pixi Texture (a RenderTexture) or TextureSource, made now if Pixi has not yet.
  const textureOf = (texture) => {
    const source = texture?.source ?? texture;
    const gpu = source ? renderer.texture.getGpuSource(source) : null;
    if (!gpu) throw new Error('crtforge-presets/pixi: Pixi has no GPU texture for this texture');
    return gpu;
  };
  // Pixi submits its work when a render call ends: nothing of it waits to be flushed.
  return createFrameworkPass(device, name, { format, textureOf });
}
