// Starts `urdftool server` (on PATH) for robot files and their companions.
const { LanguageClient } = require("vscode-languageclient/node");

let client;

exports.activate = function () {
  client = new LanguageClient(
    "urdftool",
    "urdftool",
    { command: "urdftool", args: ["server"] },
    {
      documentSelector: [
        { scheme: "file", pattern: "**/*.{urdf,xacro,srdf}" },
        // the SolidWorks exporter writes NAME.URDF; the server reads robot names in any case
        { scheme: "file", pattern: "**/*.{URDF,XACRO}" },
        { scheme: "file", pattern: "**/*.{yaml,yml}" },
      ],
    },
  );
  return client.start();
};

exports.deactivate = function () {
  return client ? client.stop() : undefined;
};
