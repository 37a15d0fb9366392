// mtmotion calculators for documentation pages: custom elements with editable
// inputs and a live result, each in its own shadow DOM (the host page's
// styles are never touched). All elements on a page share one wasm instance.
//
//   <script type="module" src="mtmotion-embed.js"></script>
//   <mt-radius-loss feed="2000" radius="10" ta="0.064" t="0.03"></mt-radius-loss>
//
// The elements only gather inputs and show results: every number comes from
// the same JS API as the workbench page, built as the small embed module
// (cargo --no-default-features: only the functions below are exported; see
// docs/performance.md).
import init, * as wasm from './pkg/mtmotion_embed.js';

let core;
/** The one shared instance (loaded on first use). */
export function loadCore() {
  core ??= init({ module_or_path: new URL('./pkg/mtmotion_embed_bg.wasm', import.meta.url) }).then(() => wasm);
  return core;
}

const STYLE = `
:host { display: block; margin: 1em 0; font: 14px/1.4 system-ui, sans-serif; color: #1d232b; }
.box { border: 1px solid #d9dee4; border-radius: 8px; padding: .7em .9em; background: #fbfcfd; }
.title { font-weight: 600; margin-bottom: .4em; }
form { display: flex; flex-wrap: wrap; gap: .4em .9em; align-items: flex-end; }
label { display: flex; flex-direction: column; font-size: .85em; color: #5b6673; }
input { font: inherit; width: 7.5em; padding: .2em .35em; border: 1px solid #c8d0d9; border-radius: 4px; color: #1d232b; }
textarea { font: 12px/1.3 ui-monospace, monospace; width: 100%; min-height: 7em; border: 1px solid #c8d0d9; border-radius: 4px; }
label.wide { flex-basis: 100%; }
output { display: block; margin-top: .5em; font-size: 1.05em; }
output b { font-variant-numeric: tabular-nums; }
.err { color: #b3261e; }
.note { color: #5b6673; font-size: .85em; }
`;

/** Base of every calculator: `fields` become attributes and inputs. */
class Calculator extends HTMLElement {
  static title = '';
  static fields = []; // { name, label, unit, value, step?, text? }
  static get observedAttributes() {
    return this.fields.map((f) => f.name);
  }

  connectedCallback() {
    if (this.shadowRoot) return;
    const C = /** @type {typeof Calculator} */ (this.constructor);
    const root = this.attachShadow({ mode: 'open' });
    root.innerHTML = `<style>${STYLE}</style><div class="box" part="box"><div class="title"></div><form></form><output part="result" aria-live="polite">…</output></div>`;
    root.querySelector('.title').textContent = this.getAttribute('title') || C.title;
    const form = root.querySelector('form');
    this.inputs = {};
    for (const f of C.fields) {
      const label = document.createElement('label');
      label.textContent = f.unit ? `${f.label} [${f.unit}]` : f.label;
      const input = document.createElement(f.text ? 'textarea' : 'input');
      if (f.text) label.className = 'wide';
      else Object.assign(input, { type: 'number', step: f.step || 'any' });
      input.name = f.name;
      input.value = this.initial(f);
      input.addEventListener('input', () => this.update());
      label.append(input);
      form.append(label);
      this.inputs[f.name] = input;
    }
    form.addEventListener('submit', (e) => e.preventDefault());
    this.output = root.querySelector('output');
    this.update();
  }

  initial(f) {
    if (this.hasAttribute(f.name)) return this.getAttribute(f.name);
    if (f.text) return (this.textContent || '').trim() || f.value;
    return String(f.value);
  }

  attributeChangedCallback(name, _old, value) {
    if (this.inputs?.[name] && this.inputs[name].value !== value) {
      this.inputs[name].value = value;
      this.update();
    }
  }

  values() {
    const v = {};
    for (const f of /** @type {typeof Calculator} */ (this.constructor).fields) v[f.name] = f.text ? this.inputs[f.name].value : Number(this.inputs[f.name].value);
    return v;
  }

  /**
   * The result for the current input values; each calculator defines it.
   * @param {object} _api the loaded core
   * @param {Record<string, number | string>} _values the inputs by field name
   * @returns {{ html: string, value: number }}
   */
  compute(_api, _values) {
    throw new Error(`${this.localName}: no compute()`);
  }

  async update() {
    const seq = (this.seq = (this.seq || 0) + 1);
    try {
      const api = await loadCore();
      if (seq !== this.seq) return;
      const { html, value } = this.compute(api, this.values());
      this.output.innerHTML = html;
      this.output.classList.remove('err');
      this.value = value;
      this.dataset.value = String(value);
    } catch (e) {
      this.output.textContent = (e && e.message) || String(e);
      this.output.classList.add('err');
      this.value = NaN;
      delete this.dataset.value;
    }
    this.dispatchEvent(new CustomEvent('mt-result', { detail: this.value }));
  }
}

const num = (x, d = 3) => (Number.isFinite(x) ? x.toFixed(d) : '—');

customElements.define(
  'mt-radius-loss',
  class extends Calculator {
    static title = 'Radius loss of a circle (Qiu, Eq. 3)';
    static fields = [
      { name: 'feed', label: 'Feed F', unit: 'mm/min', value: 2000 },
      { name: 'radius', label: 'Radius R', unit: 'mm', value: 10 },
      { name: 'ta', label: 'Acc/dec time tA', unit: 's', value: 0.064, step: 0.001 },
      { name: 't', label: 'Servo lag T', unit: 's', value: 0.03, step: 0.001 },
    ];
    compute(api, v) {
      const dr = api.radiusReduction({ feed: v.feed, radius: v.radius, tA: v.ta, T: v.t });
      return { value: dr * 1000, html: `Δr = <b>${num(dr * 1000, 2)} µm</b> <span class="note">(the circle comes out ${num(dr * 1000, 2)} µm smaller in radius)</span>` };
    }
  },
);

customElements.define(
  'mt-torque-limit',
  class extends Calculator {
    static title = 'Torque-saturation limit of a direct-drive C axis (Suzuki, Figs. 17 and 21)';
    static fields = [
      { name: 'inertia', label: 'J + J1', unit: 'kg·m²', value: 5.9, step: 0.1 },
      { name: 'torque-max', label: 'Torque limit', unit: 'N·m', value: 725 },
      { name: 'accel-time', label: 'Acc/dec time', unit: 's', value: 0.064, step: 0.001 },
      { name: 'feed', label: 'Feed at cutting point F_C', unit: 'mm/min', value: 200 },
    ];
    compute(api, v) {
      // The nmv5000 C-axis servo (suzuki Table 1) with the load J1 = (J + J1) − J.
      const [p] = api.torqueSaturation('nmv5000', {
        j1: [v.inertia - api.axisInertia('nmv5000', 'c')],
        torqueMax: v['torque-max'],
        accelTime: v['accel-time'],
        feedAtCuttingPoint: v.feed,
      });
      return {
        value: p.rcMin,
        html: `Saturates above <b>ω = ${num(p.omegaSat, 2)} rad/s</b> (α = ${num(p.accelSat, 1)} rad/s²): smallest radius of curvature <b>R<sub>C,min</sub> = ${num(p.rcMin, 3)} mm</b> at F<sub>C</sub> = ${v.feed} mm/min.`,
      };
    }
  },
);

customElements.define(
  'mt-circularity',
  class extends Calculator {
    static title = 'ISO 230-4 circular deviation of a ball-bar trace';
    static fields = [{ name: 'trace', label: 'Trace (CSV or TSV: angle and deviation, or X and Y)', text: true, value: '' }];
    compute(api, v) {
      const result = api.circularDeviation(api.parseBallbarTrace(v.trace));
      const g = Math.max(...result.runs.map((r) => r.gUm));
      const runs = result.runs.map((r) => `${r.direction.toUpperCase()}: G = <b>${num(r.gUm, 2)} µm</b> (F ${num(r.fMinUm, 2)} … ${num(r.fMaxUm, 2)} µm)`).join('; ');
      const h = result.hUm === null ? '' : `; hysteresis H = <b>${num(result.hUm, 2)} µm</b>`;
      return { value: g, html: `${runs}${h}` };
    }
  },
);

customElements.define(
  'mt-travel-bias',
  class extends Calculator {
    static title = 'Bias of a rotary-axis centre estimate from a limited travel range (Takayama, §2.1)';
    static fields = [
      { name: 'range', label: 'Travel range', unit: '°', value: 180 },
      { name: 'order', label: 'Harmonic order', unit: '', value: 2, step: 1 },
      { name: 'amplitude', label: 'Harmonic amplitude', unit: 'µm', value: 5 },
      { name: 'radius', label: 'Bar length', unit: 'mm', value: 100 },
    ];
    compute(api, v) {
      const [p] = api.travelRangeSweep({
        offset: { z: 0, x: 0 },
        harmonics: [{ order: v.order, amplitude: v.amplitude / 1000, phase: 0 }],
        ranges: [v.range],
        radius: v.radius,
        samples: 1000,
      });
      const bias = Math.hypot(p.errorZ, p.errorX) * 1000;
      return {
        value: bias,
        html: `Centre estimate off by <b>${num(bias, 2)} µm</b> (Z ${num(p.errorZ * 1000, 2)} µm, X ${num(p.errorX * 1000, 2)} µm) over ${v.range}° of travel.`,
      };
    }
  },
);
