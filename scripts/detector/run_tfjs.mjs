// Runs the original TF.js graph model on CPU (the pure JavaScript backend) for
// verify.py and verify_segmenter.py: reads an input blob, writes each output as float32.
// Usage: node run_tfjs.mjs MODEL.json INPUT.bin OUT_DIR [--shape 1,H,W,3] [--dtype float32|int32]
//                          [--outputs NODE,NODE...]
// The input is raw float32 (or int32, e.g. for a uint8 image placeholder) in the given shape
// (default: the model's input shape). The outputs are the model's own, or the named nodes; each
// is written to OUT_DIR/NAME.bin with any '/' in NAME turned into '_'.
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.join(process.cwd(), 'package.json'));
const tf = require('@tensorflow/tfjs');

const [modelPath, inputPath, outDir, ...rest] = process.argv.slice(2);
const options = {};
for (let i = 0; i < rest.length; i += 2) {
  if (!rest[i].startsWith('--') || rest[i + 1] === undefined) throw new Error(`bad option ${rest[i]}`);
  options[rest[i].slice(2)] = rest[i + 1];
}
const model = JSON.parse(fs.readFileSync(modelPath, 'utf8'));
const folder = path.dirname(modelPath);
const specs = model.weightsManifest.flatMap((g) => g.weights);
const buffers = model.weightsManifest.flatMap((g) => g.paths.map((p) => fs.readFileSync(path.join(folder, p))));
const weights = Buffer.concat(buffers);

await tf.setBackend('cpu');
const graph = await tf.loadGraphModel(tf.io.fromMemory({
  modelTopology: model.modelTopology,
  weightSpecs: specs,
  weightData: weights.buffer.slice(weights.byteOffset, weights.byteOffset + weights.byteLength),
}));
const shape = options.shape ? options.shape.split(',').map(Number) : graph.inputs[0].shape;
const dtype = options.dtype || 'float32';
const raw = fs.readFileSync(inputPath);
const Array_ = dtype === 'int32' ? Int32Array : Float32Array;
const input = tf.tensor(new Array_(raw.buffer, raw.byteOffset, raw.byteLength / 4), shape, dtype);
const names = options.outputs ? options.outputs.split(',') : graph.outputs.map((o) => o.name);
const started = Date.now();
const outputs = await graph.executeAsync(input, names);
const seconds = (Date.now() - started) / 1000;
for (const [i, name] of [...names.entries()]) {
  const data = Float32Array.from((Array.isArray(outputs) ? outputs[i] : outputs).dataSync());
  const file = `${name.replace(/:0$/, '').replaceAll('/', '_')}.bin`;
  fs.writeFileSync(path.join(outDir, file), Buffer.from(data.buffer));
}
console.log(`tfjs: ${names.length} outputs in ${seconds.toFixed(1)} s`);
