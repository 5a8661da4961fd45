// The example page: loads a crtforge export (manifest.json + wgsl/<preset>.wgsl), shows a test
// picture or an uploaded image through the chosen preset on a WebGPU canvas, with a slider per
// runtime param. The export directory is ../../out/export/ unless the page has ?export=DIR;
// ?preset=NAME picks the first preset.
import { createCrtPass } from './crt-webgpu.mjs';

const $ = (id) => document.getElementById(id);
const query = new URLSearchParams(location.search);
const exportDir = new URL((query.get('export') ?? '../../out/export/').replace(/\/?$/, '/'), location.href);

function showMessage(text) {
  $('message').textContent = text;
  $('message').style.display = text ? 'block' : 'none';
}

// A recognisable 320x240 picture: SMPTE-like colour bars, a grey ramp, a checker and some text.
function drawTestPicture() {
  const canvas = document.createElement('canvas');
  canvas.width = 320;
  canvas.height = 240;
  const g = canvas.getContext('2d');
  const bars = ['#c0c0c0', '#c0c000', '#00c0c0', '#00c000', '#c000c0', '#c00000', '#0000c0'];
  bars.forEach((c, i) => { g.fillStyle = c; g.fillRect((i * 320) / 7, 0, 320 / 7 + 1, 120); });
  for (let x = 0; x < 320; ++x) {  // grey ramp
    const v = Math.round((x / 319) * 255);
    g.fillStyle = `rgb(${v},${v},${v})`;
    g.fillRect(x, 120, 1, 30);
  }
  for (let y = 150; y < 240; y += 10)  // checker
    for (let x = 0; x < 160; x += 10) {
      g.fillStyle = ((x + y) / 10) % 2 ? '#fff' : '#000';
      g.fillRect(x, y, 10, 10);
    }
  g.fillStyle = '#102040';
  g.fillRect(160, 150, 160, 90);
  g.fillStyle = '#ffd040';
  g.font = 'bold 24px monospace';
  g.textAlign = 'center';
  g.fillText('crtforge', 240, 185);
  g.font = '14px monospace';
  g.fillStyle = '#80ff80';
  g.fillText('PRESS START', 240, 215);
  g.strokeStyle = '#fff';
  g.beginPath();
  g.arc(160, 75, 40, 0, 2 * Math.PI);
  g.stroke();
  return canvas;
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
    const response = await fetch(new URL('manifest.json', exportDir));
    if (!response.ok) throw new Error(`HTTP ${response.status}`);
    manifest = await response.json();
  } catch (e) {
    return showMessage(`Cannot load ${new URL('manifest.json', exportDir)} (${e.message}).\nRun scripts/run-main.sh or build/crtforge export --out out/export, serve the repository root, or pass ?export=DIR.`);
  }
  const names = Object.keys(manifest.presets).filter((n) => manifest.presets[n].passes?.length === 1 && manifest.presets[n].passes[0].targets?.wgsl);
  if (!names.length) return showMessage('The manifest has no preset with a wgsl target (export with --target wgsl or all targets).');

  const canvas = $('screen');
  const context = canvas.getContext('webgpu');
  const format = navigator.gpu.getPreferredCanvasFormat();
  context.configure({ device, format, alphaMode: 'opaque' });

  // The source picture, as an rgba8unorm texture (values used as stored, like crtforge's inputs).
  let source = null;
  async function setPicture(image) {
    const bitmap = await createImageBitmap(image);
    source?.destroy();
    source = device.createTexture({
      size: [bitmap.width, bitmap.height],
      format: 'rgba8unorm',
      usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST | GPUTextureUsage.RENDER_ATTACHMENT,
    });
    device.queue.copyExternalImageToTexture({ source: bitmap }, { texture: source }, [bitmap.width, bitmap.height]);
  }
  await setPicture(drawTestPicture());
  $('test-picture').onclick = () => setPicture(drawTestPicture());
  $('image').onchange = async (e) => {
    const file = e.target.files[0];
    if (file) await setPicture(file).catch((err) => showMessage(`Cannot read that image: ${err.message}`));
  };

  // The CRT pass of the chosen preset, and a control per runtime param.
  let crt = null;
  const wgslCache = new Map();
  async function choosePreset(name) {
    const preset = manifest.presets[name].passes[0];
    if (!wgslCache.has(name)) {
      const response = await fetch(new URL(preset.targets.wgsl.shader, exportDir));
      if (!response.ok) throw new Error(`cannot fetch ${preset.targets.wgsl.shader}: HTTP ${response.status}`);
      wgslCache.set(name, await response.text());
    }
    const next = createCrtPass(device, { wgsl: wgslCache.get(name), preset, format });
    const error = (await next.compilationInfo()).find((m) => m.type === 'error');
    if (error) throw new Error(`${name}.wgsl ${error.lineNum}:${error.linePos}: ${error.message}`);
    crt?.destroy();
    crt = next;
    showMessage('');
    $('doc').textContent = preset.doc ?? '';
    buildControls();
  }

  function buildControls() {
    const box = $('params');
    box.replaceChildren();
    const params = crt.params();
    if (!params.length) box.textContent = 'This preset has no runtime parameters.';
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
        input.oninput = () => crt.setParam(p.name, [1, 3, 5].map((i) => parseInt(input.value.slice(i, i + 2), 16) / 255));
      } else {
        input.type = 'range';
        const [min, max] = p.range ?? [0, Math.max(1, p.default * 2)];
        Object.assign(input, { min, max, step: p.step ?? (p.type === 'int' ? 1 : (max - min) / 100), value: p.value });
        const show = () => { value.textContent = String(Number(input.value)) + (p.unit ? ` ${p.unit}` : ''); };
        input.oninput = () => { crt.setParam(p.name, Number(input.value)); show(); };
        show();
      }
      const doc = document.createElement('small');
      doc.textContent = p.doc;
      row.append(label, input, doc);
      box.append(row);
    }
  }

  $('reset').onclick = () => {
    for (const p of crt.params()) crt.setParam(p.name, p.default);
    buildControls();
  };
  const select = $('preset');
  for (const n of names) select.add(new Option(n, n));
  select.value = names.includes(query.get('preset')) ? query.get('preset') : names.includes('classic') ? 'classic' : names[0];
  select.onchange = () => choosePreset(select.value).catch((e) => showMessage(e.message));
  await choosePreset(select.value).catch((e) => showMessage(e.message));

  // Draw every animation frame; time runs from page load.
  const start = performance.now();
  function frame() {
    const width = Math.max(1, Math.round(canvas.clientWidth * devicePixelRatio));
    const height = Math.max(1, Math.round(canvas.clientHeight * devicePixelRatio));
    if (canvas.width !== width || canvas.height !== height) Object.assign(canvas, { width, height });
    requestAnimationFrame(frame);
    if (!crt || !source) return;
    const encoder = device.createCommandEncoder();
    crt.encode(encoder, {
      source, target: context.getCurrentTexture().createView(), width, height,
      time: (performance.now() - start) / 1000,
    });
    device.queue.submit([encoder.finish()]);
  }
  requestAnimationFrame(frame);
}

main().catch((e) => showMessage(`Error: ${e.message}`));
