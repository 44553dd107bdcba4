-- Run by `nvim --headless` (see run_neovim_test.cmake): Neovim's own LSP
-- client starts cncc-lsp, opens a file with an error, waits for the
-- diagnostics, asks for a hover and a completion, and writes what it got
-- to a JSON file for the test to check. Paths come from the environment.
local server = assert(os.getenv('CNCC_LSP'), 'CNCC_LSP is not set')
local document = assert(os.getenv('CNCC_NVIM_DOCUMENT'), 'CNCC_NVIM_DOCUMENT is not set')
local result_file = assert(os.getenv('CNCC_NVIM_RESULT'), 'CNCC_NVIM_RESULT is not set')

local results = { problems = {} }

local function finish()
  local file = assert(io.open(result_file, 'w'))
  file:write(vim.fn.json_encode(results))
  file:close()
  vim.cmd('qall!')
end

local function problem(text)
  table.insert(results.problems, text)
end

-- Guards every step: a Lua error still writes the results and quits.
local function run()
  vim.cmd('edit ' .. vim.fn.fnameescape(document))
  local buffer = vim.api.nvim_get_current_buf()
  local client_id = vim.lsp.start_client({
    name = 'cncc',
    cmd = { server },
    root_dir = vim.fn.fnamemodify(document, ':p:h'),
  })
  if not client_id then
    problem('the client did not start')
    return
  end
  vim.lsp.buf_attach_client(buffer, client_id)

  local received = vim.wait(10000, function()
    return #vim.diagnostic.get(buffer) > 0
  end, 20)
  if not received then
    problem('no diagnostics within 10 s')
  end
  results.diagnostics = {}
  for _, diagnostic in ipairs(vim.diagnostic.get(buffer)) do
    table.insert(results.diagnostics, {
      line = diagnostic.lnum,
      column = diagnostic.col,
      end_column = diagnostic.end_col,
      severity = diagnostic.severity,
      message = diagnostic.message,
      code = diagnostic.code,
      source = diagnostic.source,
    })
  end

  local uri = vim.uri_from_bufnr(buffer)
  local function ask(method, line, character)
    local params = { textDocument = { uri = uri }, position = { line = line, character = character } }
    local responses, failure = vim.lsp.buf_request_sync(buffer, method, params, 5000)
    if not responses or not responses[client_id] then
      problem(method .. ' got no response: ' .. tostring(failure))
      return nil
    end
    if responses[client_id].err then
      problem(method .. ' failed: ' .. vim.inspect(responses[client_id].err))
    end
    return responses[client_id].result
  end

  -- `nurbs` on line 9 (0-based 8), and completion after `points=P`.
  local hover = ask('textDocument/hover', 8, 10)
  results.hover = hover and hover.contents and hover.contents.value or vim.NIL
  local completion = ask('textDocument/completion', 8, 31)
  results.completion = {}
  for _, item in ipairs(completion and (completion.items or completion) or {}) do
    table.insert(results.completion, item.label)
  end
  results.client_name = vim.lsp.get_client_by_id(client_id).name
end

local ok, message = pcall(run)
if not ok then
  problem('Lua error: ' .. tostring(message))
end
finish()
