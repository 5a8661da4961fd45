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
import { createFrameworkPass } from './framework-pass.mjs';

export async function createThreeCrtPass(renderer, name, { format = 'rgba8unorm' } = {}) {
  const device = renderer?.backend?.device;
  if (!device) throw new Error('crtforge-presets/three: needs a WebGPURenderer after `await renderer.init()` (the WebGPU backend)');
  // The GPUTexture three made for a RenderTarget's texture, made now (by a clear) if three has not yet.
  const textureOf = (renderTarget) => {
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
  return createFrameworkPass(device, name, { format, textureOf });
}
