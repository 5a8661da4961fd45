// What every framework adapter (three.mjs, pixi.mjs, babylon.mjs) shares: the preset on the
// framework's GPUDevice, one scene per target format (a pipeline is made for one format) with the
// params set so far replayed on a scene made later, and the pass object the adapters return.
// Each adapter brings only how its framework's textures become GPUTextures (`textureOf`) and what
// must reach the queue before the pass (`beforeSubmit`: work the framework has recorded).
import { loadCrtPreset } from './index.mjs';

export async function createFrameworkPass(device, name, { format, textureOf, beforeSubmit = () => {} }) {
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
  return {
    // The scene made for `format` (setParam below reaches every format's scene).
    scene: first,
    params: () => first.params(),
    setParam(param, value) {
      first.setParam(param, value);  // throws, naming the problem, for a bad name or value
      values.set(param, value);
      for (const scene of scenes.values()) scene.then((s) => s.setParam(param, value));
    },
    // Draws `input` through the preset into `output`, at output's size, on the device's queue.
    async render(input, output, { frame, time, fit } = {}) {
      const target = textureOf(output);
      const scene = await sceneFor(target.format);
      const source = textureOf(input);
      beforeSubmit();
      const encoder = device.createCommandEncoder({ label: `crtforge ${name}` });
      scene.encode(encoder, { source, target: target.createView(), width: target.width, height: target.height, frame, time, fit });
      device.queue.submit([encoder.finish()]);
    },
    // Lower level: records the pass into your encoder, onto any view of `format`.
    encode(encoder, options) {
      first.encode(encoder, options);
    },
    // The GPUTexture behind one of the framework's textures (for encode()'s `source`).
    textureOf,
    destroy() {
      for (const scene of scenes.values()) scene.then((s) => s.destroy());
      scenes.clear();
    },
  };
}
