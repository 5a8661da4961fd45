// The screenshot page: one preset, the test picture, rendered by the browser's own WebGPU through
// the exported npm package (<export>/npm: loadCrtPreset), read back and written into #out as a PNG
// data URL, or "error: ..." when anything fails. Query: package (the npm folder's URL, default
// ../../out/export/npm/), preset (classic), width x height of the frame (640x480), frames drawn
// (1; feedback presets need a few), time in seconds (0.5).
import { drawTestPicture } from './test-picture.mjs';

const out = document.getElementById('out');
const query = new URLSearchParams(location.search);

async function render() {
  const packageUrl = new URL((query.get('package') ?? '../../out/export/npm/').replace(/\/?$/, '/'), location.href);
  const pkg = await import(new URL('index.mjs', packageUrl).href);
  const name = query.get('preset') ?? 'classic';
  const width = Number(query.get('width') ?? 640), height = Number(query.get('height') ?? 480);
  const frames = Number(query.get('frames') ?? 1), time = Number(query.get('time') ?? 0.5);
  if (!navigator.gpu) throw new Error('this browser has no navigator.gpu (WebGPU)');
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new Error('no WebGPU adapter');
  const device = await adapter.requestDevice();

  const manifest = await pkg.loadManifest();
  const [w, h] = manifest.presets[name]?.scene?.source?.size ?? [320, 240];
  const source = device.createTexture({
    size: [w, h], format: 'rgba8unorm',
    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | GPUTextureUsage.RENDER_ATTACHMENT,
  });
  device.queue.copyExternalImageToTexture({ source: drawTestPicture(w, h) },
    { texture: source, colorSpace: 'srgb', premultipliedAlpha: false }, [w, h]);
  const crt = await pkg.loadCrtPreset(device, name, { format: 'rgba8unorm' });
  const target = device.createTexture({
    size: [width, height], format: 'rgba8unorm', usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC,
  });
  for (let frame = 0; frame < frames; ++frame) {
    const encoder = device.createCommandEncoder();
    crt.encode(encoder, { source, target: target.createView(), width, height, frame, time });
    device.queue.submit([encoder.finish()]);
  }
  const bytesPerRow = Math.ceil((width * 4) / 256) * 256;
  const readback = device.createBuffer({ size: bytesPerRow * height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
  const encoder = device.createCommandEncoder();
  encoder.copyTextureToBuffer({ texture: target }, { buffer: readback, bytesPerRow }, [width, height]);
  device.queue.submit([encoder.finish()]);
  await readback.mapAsync(GPUMapMode.READ);
  const rows = new Uint8Array(readback.getMappedRange());
  const pixels = new ImageData(width, height);
  for (let y = 0; y < height; ++y) pixels.data.set(rows.subarray(y * bytesPerRow, y * bytesPerRow + width * 4), y * width * 4);
  for (let i = 3; i < pixels.data.length; i += 4) pixels.data[i] = 255;  // shown over black, like a screen
  const canvas = document.createElement('canvas');
  Object.assign(canvas, { width, height });
  canvas.getContext('2d').putImageData(pixels, 0, 0);
  return canvas.toDataURL('image/png');
}

render().then((url) => { out.textContent = url; }, (e) => { out.textContent = `error: ${e.message}`; });
