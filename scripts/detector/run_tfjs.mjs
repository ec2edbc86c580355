// Runs the original TF.js graph model on CPU (the pure JavaScript backend) for
// verify.py: reads a float32 NCHW input blob, writes each output as float32.
// Usage: node run_tfjs.mjs MODEL.json INPUT.bin OUT_DIR
import fs from 'node:fs';
import path from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(path.join(process.cwd(), 'package.json'));
const tf = require('@tensorflow/tfjs');

const [modelPath, inputPath, outDir] = process.argv.slice(2);
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
const shape = graph.inputs[0].shape;
const raw = fs.readFileSync(inputPath);
const input = tf.tensor(new Float32Array(raw.buffer, raw.byteOffset, raw.byteLength / 4), shape);
const names = graph.outputs.map((o) => o.name);
const outputs = await graph.executeAsync(input, names);
for (const [i, name] of names.entries()) {
  const data = outputs[i].dataSync();
  fs.writeFileSync(path.join(outDir, `${name.replace(/:0$/, '')}.bin`), Buffer.from(data.buffer));
}
console.log(`tfjs: ${names.length} outputs`);
