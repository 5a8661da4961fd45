// The example page: loads a crtforge export (manifest.json, wgsl/*.wgsl, luts/*.png) and shows a
// test picture or an uploaded image through the chosen preset on a WebGPU canvas, animated, with
// a control per runtime param. Every preset whose passes all have a WGSL target is offered; it
// runs as a whole scene (createCrtScene: its passes, feedback, LUTs). The export directory is
// ../../out/export/ unless the page has ?export=DIR; ?preset=NAME picks the first preset.
import { createCrtScene } from './crt-webgpu.mjs';
import { drawTestPicture } from './test-picture.mjs';

const $ = (id) => document.getElementById(id);
const query = new URLSearchParams(location.search);
const exportDir = new URL((query.get('export') ?? '../../out/export/').replace(/\/?$/, '/'), location.href);

// Texel bytes must arrive as stored (crtforge's goldens and LUTs are made that way): no colour
// space conversion and no premultiplication on either side of copyExternalImageToTexture.
const BITMAP_OPTIONS = { colorSpaceConversion: 'none', premultiplyAlpha: 'none' };
const UPLOAD_OPTIONS = { colorSpace: 'srgb', premultipliedAlpha: false };

function showMessage(text) {
  $('message').textContent = text;
  $('message').style.display = text ? 'block' : 'none';
}

// Where the moving sprite is at `frame`: bouncing off the picture's edges, a whole number of
// pixels per frame (so trails, which work per frame, look the same at any refresh rate).
function spriteAt(frame, width, height, size) {
  const bounce = (t, span) => (span <= 0 ? 0 : span - Math.abs((t % (2 * span)) - span));
  const speed = Math.max(1, Math.round(width / 160));
  return { x: bounce(frame * speed, width - size), y: bounce(frame * Math.max(1, Math.round(speed * 0.6)), height - size) };
}

async function fetchOk(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`cannot fetch ${url}: HTTP ${response.status}`);
  return response;
}

async function main() {
  if (!navigator.gpu) {
    showMessage('This browser has no WebGPU (navigator.gpu is missing). Use a recent Chrome/Edge, or Firefox/Safari with WebGPU enabled, over http://localhost or https.');
    return;
  }
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) return showMessage('WebGPU is present but no GPU adapter is available.');
  const device = await adapter.requestDevice();
  device.addEventListener('uncapturederror', (e) => showMessage(`WebGPU error: ${e.error.message}`));
  device.lost.then((info) => showMessage(`WebGPU device lost: ${info.message}`));

  let manifest;
  try {
    manifest = await (await fetchOk(new URL('manifest.json', exportDir))).json();
  } catch (e) {
    return showMessage(`Cannot load ${new URL('manifest.json', exportDir)} (${e.message}).\nRun scripts/run-main.sh or build/crtforge export --out out/export, serve the repository root, or pass ?export=DIR.`);
  }
  // Every preset the module can run: all of its passes have a WGSL shader.
  const names = Object.keys(manifest.presets ?? {}).filter((n) => {
    const passes = manifest.presets[n].passes;
    return passes?.length > 0 && passes.every((p) => p.targets?.wgsl);
  });
  if (!names.length) return showMessage('The manifest has no preset with a wgsl target (export with --target wgsl or all targets).');

  const select = $('preset');
  const canvas = $('screen');
  const context = canvas.getContext('webgpu');
  const format = navigator.gpu.getPreferredCanvasFormat();
  context.configure({ device, format, alphaMode: 'opaque' });

  // ---- the source picture ----
  // `picture` is what is shown: the test picture (a canvas) or the user's image (an ImageBitmap).
  // It is copied into `source`, an rgba8unorm texture (values used as stored, like crtforge's
  // inputs) — once when it changes, or every frame through `compose` when the sprite moves over it.
  let shown = null;  // the manifest entry of the preset on screen
  let userImage = null, picture = null, pictureDirty = true;
  let source = null;
  const compose = document.createElement('canvas');
  const composeContext = compose.getContext('2d');

  function upload(image, width, height) {
    if (!source || source.width !== width || source.height !== height) {
      source?.destroy();
      source = device.createTexture({
        label: 'picture', size: [width, height], format: 'rgba8unorm',
        usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | GPUTextureUsage.RENDER_ATTACHMENT,
      });
    }
    device.queue.copyExternalImageToTexture({ source: image }, { texture: source, ...UPLOAD_OPTIONS }, [width, height]);
  }

  function updateSource(frame) {
    if (!picture) return;
    const { width, height } = picture;
    if ($('sprite').checked) {
      if (compose.width !== width || compose.height !== height) Object.assign(compose, { width, height });
      composeContext.clearRect(0, 0, width, height);
      composeContext.drawImage(picture, 0, 0);
      const size = Math.max(2, Math.round(height / 20));
      const { x, y } = spriteAt(frame, width, height, size);
      composeContext.fillStyle = '#ffffff';
      composeContext.fillRect(x, y, size, size);
      upload(compose, width, height);
      pictureDirty = true;  // the plain picture has to go back in when the sprite is turned off
    } else if (pictureDirty) {
      upload(picture, width, height);
      pictureDirty = false;
    }
  }

  // The test picture is drawn at the preset's source size when the manifest gives one (e.g.
  // super-win's 256x224), so per-texel effects look as designed.
  function usePicture() {
    const size = shown?.scene?.source?.size;
    picture = userImage ?? drawTestPicture(...(size ?? [320, 240]));
    pictureDirty = true;
  }

  $('test-picture').onclick = () => {
    userImage?.close();
    userImage = null;
    $('image').value = '';
    usePicture();
  };
  $('image').onchange = async (e) => {
    const file = e.target.files[0];
    if (!file) return;
    try {
      const bitmap = await createImageBitmap(file, BITMAP_OPTIONS);
      userImage?.close();
      userImage = bitmap;
      usePicture();
    } catch (err) {
      showMessage(`Cannot read that image: ${err.message}`);
    }
  };

  // ---- the export's files, fetched once each ----
  // Promises are cached (so two quick preset switches share one load); a failed load is
  // forgotten, so choosing the preset again retries it.
  const loads = new Map();  // path -> Promise of its WGSL text or LUT texture (LUTs are kept)
  function once(path, load) {
    if (!loads.has(path)) loads.set(path, load(new URL(path, exportDir)).catch((e) => { loads.delete(path); throw e; }));
    return loads.get(path);
  }

  const loadWgsl = (path) => once(path, async (url) => (await fetchOk(url)).text());

  const loadLut = (path) => once(path, async (url) => {
    const bitmap = await createImageBitmap(await (await fetchOk(url)).blob(), BITMAP_OPTIONS);
    const texture = device.createTexture({
      label: path, size: [bitmap.width, bitmap.height], format: 'rgba8unorm',
      usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | GPUTextureUsage.RENDER_ATTACHMENT,
    });
    device.queue.copyExternalImageToTexture({ source: bitmap }, { texture, ...UPLOAD_OPTIONS }, [bitmap.width, bitmap.height]);
    bitmap.close();
    return texture;
  });

  // ---- the scene of the chosen preset ----
  let scene = null;
  let frame = 0;       // frames drawn by this scene: drives feedback and frame-dependent effects
  let choosing = 0;    // the latest choosePreset call; an older one that finishes later is dropped

  async function choosePreset(name) {
    const ticket = ++choosing;
    const preset = manifest.presets[name];
    const wgsl = {}, luts = {};
    for (const pass of preset.passes) wgsl[pass.alias] = await loadWgsl(pass.targets.wgsl.shader);
    for (const [lutName, lut] of Object.entries(preset.luts ?? {})) luts[lutName] = await loadLut(lut.file);
    if (ticket !== choosing) return;

    const next = createCrtScene(device, { preset, wgsl, luts, format });
    for (const pass of next.passes) {
      const error = (await pass.compilationInfo()).find((m) => m.type === 'error');
      if (error) {
        next.destroy();
        throw new Error(`${pass.alias} (${preset.passes.find((p) => p.alias === pass.alias).targets.wgsl.shader}) ${error.lineNum}:${error.linePos}: ${error.message}`);
      }
    }
    if (ticket !== choosing) return next.destroy();

    scene?.destroy();  // its pass textures and uniform buffers; the LUTs stay cached
    scene = next;
    shown = preset;
    frame = 0;
    showMessage('');
    $('doc').textContent = preset.doc ?? '';
    $('passes').textContent = preset.passes.length > 1 ? `Passes: ${preset.passes.map((p) => p.alias).join(' → ')}` : '';
    $('fit').options[0].text = `preset default (${preset.scene?.display?.fit ?? 'stretch'})`;
    if (!userImage) usePicture();  // the test picture follows the preset's source size
    buildControls();
  }

  // One control per runtime param name: setParam sets it on every pass that has it.
  function distinctParams() {
    const seen = new Map();
    for (const p of scene.params()) if (!seen.has(p.name)) seen.set(p.name, p);
    return [...seen.values()];
  }

  function setParam(name, value) {
    try {
      scene?.setParam(name, value);
    } catch (e) {
      showMessage(e.message);
    }
  }

  function buildControls() {
    const box = $('params');
    box.replaceChildren();
    const params = distinctParams();
    if (!params.length) box.textContent = 'This preset has no runtime parameters.';
    const multiPass = scene.passes.length > 1;
    for (const p of params) {
      const row = document.createElement('div');
      row.className = 'param';
      const label = document.createElement('label');
      const value = document.createElement('span');
      value.className = 'value';
      label.append(p.name, value);
      const input = document.createElement('input');
      input.id = `param-${p.name}`;
      label.htmlFor = input.id;
      if (Array.isArray(p.default)) {  // a colour: [r, g, b] in 0..1
        input.type = 'color';
        input.value = '#' + p.value.map((c) => Math.round(c * 255).toString(16).padStart(2, '0')).join('');
        input.oninput = () => setParam(p.name, [1, 3, 5].map((i) => parseInt(input.value.slice(i, i + 2), 16) / 255));
      } else {
        input.type = 'range';
        const [min, max] = p.range ?? [0, Math.max(1, p.default * 2)];
        Object.assign(input, { min, max, step: p.step ?? (p.type === 'int' ? 1 : (max - min) / 100), value: p.value });
        const show = () => { value.textContent = String(Number(input.value)) + (p.unit ? ` ${p.unit}` : ''); };
        input.oninput = () => { setParam(p.name, Number(input.value)); show(); };
        show();
      }
      const doc = document.createElement('small');
      doc.textContent = multiPass ? `[${p.pass}] ${p.doc}` : p.doc;  // which pass it belongs to
      row.append(label, input, doc);
      box.append(row);
    }
  }

  $('reset').onclick = () => {
    if (!scene) return;
    for (const p of distinctParams()) setParam(p.name, p.default);
    buildControls();
  };
  $('sprite').onchange = () => { pictureDirty = true; };
  for (const n of names) select.add(new Option(n, n));
  select.value = names.includes(query.get('preset')) ? query.get('preset') : names.includes('classic') ? 'classic' : names[0];
  select.onchange = () => choosePreset(select.value).catch((e) => showMessage(e.message));
  usePicture();
  await choosePreset(select.value).catch((e) => showMessage(e.message));

  // Draw every animation frame: the frame number advances by one per frame drawn (feedback such
  // as super-win's trails decays per frame); time runs in seconds from page load.
  const start = performance.now();
  function draw() {
    requestAnimationFrame(draw);
    const width = Math.max(1, Math.round(canvas.clientWidth * devicePixelRatio));
    const height = Math.max(1, Math.round(canvas.clientHeight * devicePixelRatio));
    if (canvas.width !== width || canvas.height !== height) Object.assign(canvas, { width, height });
    if (!scene) return;
    try {
      updateSource(frame);
      const encoder = device.createCommandEncoder();
      scene.encode(encoder, {
        source, target: context.getCurrentTexture().createView(), width, height,
        frame, time: (performance.now() - start) / 1000, fit: $('fit').value || undefined,
      });
      device.queue.submit([encoder.finish()]);
      ++frame;
    } catch (e) {
      // A broken scene would throw every frame: report it once and stop drawing it.
      showMessage(`Error: ${e.message}`);
      scene.destroy();
      scene = null;
    }
  }
  requestAnimationFrame(draw);
}

main().catch((e) => showMessage(`Error: ${e.message}`));
