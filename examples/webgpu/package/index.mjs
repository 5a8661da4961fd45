// crtforge-presets: the presets of one `crtforge export`, ready for WebGPU, as an npm package.
//
//   import { loadCrtPreset } from 'crtforge-presets';
//   const crt = await loadCrtPreset(device, 'classic', { format: navigator.gpu.getPreferredCanvasFormat() });
//   crt.encode(encoder, { source, target: context.getCurrentTexture().createView(), width, height, frame, time });
//
// The package holds manifest.json (the export's manifest, WGSL entries only), wgsl/*.wgsl and
// luts/*.png, and reads them relative to this file: with fetch() in a browser or a bundler's
// dev server, with node:fs in Node (dawn.node, npm `webgpu`). Everything else is crt-webgpu.mjs,
// re-exported as it is.
import { createCrtScene, createLutTexture, mipmappedLuts } from './crt-webgpu.mjs';

export * from './crt-webgpu.mjs';

const packageRoot = new URL('./', import.meta.url);

async function readBytes(relative) {
  const url = new URL(relative, packageRoot);
  if (url.protocol === 'file:') {
    const { readFile } = await import('node:fs/promises');
    return new Uint8Array(await readFile(url));
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`crtforge-presets: ${url}: HTTP ${response.status}`);
  return new Uint8Array(await response.arrayBuffer());
}

let manifestPromise = null;

// The export's manifest (read once): presets, their passes, params, uniform layouts and LUTs.
export function loadManifest() {
  manifestPromise ??= readBytes('manifest.json').then((bytes) => JSON.parse(new TextDecoder().decode(bytes)));
  return manifestPromise;
}

// The preset names the package holds, in the manifest's order.
export async function presetNames() {
  return Object.keys((await loadManifest()).presets);
}

// A whole preset (every pass, its LUTs) as createCrtScene's scene, its files read from the package.
export async function loadCrtPreset(device, name, { format }) {
  const manifest = await loadManifest();
  const preset = manifest.presets[name];
  if (!preset) throw new Error(`crtforge-presets: no preset '${name}' (the package has: ${Object.keys(manifest.presets).join(', ')})`);
  const wgsl = {};
  for (const pass of preset.passes) wgsl[pass.alias] = new TextDecoder().decode(await readBytes(pass.targets.wgsl.shader));
  const luts = {};
  const mipmapped = mipmappedLuts(preset);  // made with their mip chains
  for (const [lutName, lut] of Object.entries(preset.luts ?? {}))
    luts[lutName] = await createLutTexture(device, await readBytes(lut.file), lut.file, { mipmap: mipmapped.has(lutName) });
  return createCrtScene(device, { preset, wgsl, luts, format });
}
