// The CDL extension's client: starts `cncc lsp` (the command is a setting)
// for .cdl files and connects VS Code's language client to it over stdio.
'use strict';

const vscode = require('vscode');
const { LanguageClient, TransportKind } = require('vscode-languageclient/node');

let client;

function serverOptions() {
  const settings = vscode.workspace.getConfiguration('cdl.server');
  const command = settings.get('command', 'cncc');
  const args = ['lsp', ...settings.get('extraArguments', [])];
  return { command, args, transport: TransportKind.stdio };
}

function activate(context) {
  const clientOptions = {
    documentSelector: [
      { scheme: 'file', language: 'cdl' },
      { scheme: 'untitled', language: 'cdl' },
    ],
  };
  client = new LanguageClient('cdl', 'CDL language server (cncc)', serverOptions(), clientOptions);
  context.subscriptions.push(
    vscode.commands.registerCommand('cdl.restartServer', () => client.restart()));
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
