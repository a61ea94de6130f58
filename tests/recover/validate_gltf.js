// Validates a glTF file with the Khronos glTF-Validator (npm package "gltf-validator",
// installed globally: run with NODE_PATH=$(npm root -g)). Prints the issue report as JSON.
// Exit: 0 no errors, 1 errors, 2 the validator failed, 77 the package is not installed.
let validator;
try {
    validator = require('gltf-validator');
} catch (e) {
    console.log('gltf-validator is not installed (npm install -g gltf-validator)');
    process.exit(77);
}
const fs = require('fs');
validator.validateBytes(new Uint8Array(fs.readFileSync(process.argv[2])), {maxIssues: 100})
    .then((report) => {
        console.log(JSON.stringify(report.issues, null, 1));
        process.exit(report.issues.numErrors > 0 ? 1 : 0);
    })
    .catch((e) => {
        console.log('validator failed: ' + e);
        process.exit(2);
    });
