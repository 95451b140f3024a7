//! `meshvol completions SHELL` and `meshvol man`: the completion scripts and the manual
//! pages, both made by clap from the command's own definition, so they never lag it.

use clap::Command;
use std::path::Path;
use std::process::ExitCode;

/// Writes the completion script for `shell` to stdout.
pub fn completions(shell: clap_complete::Shell, mut command: Command) -> ExitCode {
    let mut out = Vec::new();
    clap_complete::generate(shell, &mut command, "meshvol", &mut out);
    emit(&out)
}

/// Writes the manual page of the command, or of its subcommand `name`, to stdout.
pub fn man(mut command: Command, name: Option<&str>) -> ExitCode {
    command.build();
    let page = match name {
        None => command,
        Some(name) => match subcommand_page(&command, name) {
            Some(page) => page,
            None => {
                let names: Vec<&str> = pages(&command).map(|c| c.get_name()).collect();
                let list = names.join(", ");
                let why = match crate::nearest::nearest(name, names.iter().copied()) {
                    Some(meant) => format!("did you mean `{meant}`? (one of {list})"),
                    None => format!("one of {list}"),
                };
                eprintln!("meshvol: error: '{name}' is not a subcommand: {why}");
                return ExitCode::from(2);
            }
        },
    };
    match render(page) {
        Ok(out) => emit(&out),
        Err(e) => {
            eprintln!("meshvol: error: cannot write the manual page: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Writes every manual page into `dir` (made if missing) as `meshvol.1` and
/// `meshvol-NAME.1`, the pages `man` and `man NAME` print, and prints their paths.
pub fn man_all(mut command: Command, dir: &Path) -> ExitCode {
    command.build();
    let mut written = String::new();
    let mut write = |file: String, page: Command| -> Result<(), String> {
        let path = dir.join(file);
        let bytes = render(page).map_err(|e| format!("cannot write the manual page: {e}"))?;
        std::fs::write(&path, bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        written += &format!("{}\n", path.display());
        Ok(())
    };
    let all = std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display())).and_then(
        |()| {
            for sub in pages(&command) {
                let name = sub.get_name();
                if let Some(page) = subcommand_page(&command, name) {
                    write(format!("meshvol-{name}.1"), page)?;
                }
            }
            write("meshvol.1".to_string(), command.clone())
        },
    );
    match all {
        Ok(()) => emit(written.as_bytes()),
        Err(e) => {
            eprintln!("meshvol: error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The subcommands that have a page: all but clap's `help`.
fn pages(command: &Command) -> impl Iterator<Item = &Command> {
    command.get_subcommands().filter(|c| c.get_name() != "help" && !c.is_hide_set())
}

/// The page of subcommand `name`, titled `meshvol-NAME`.
fn subcommand_page(command: &Command, name: &str) -> Option<Command> {
    let sub = pages(command).find(|c| c.get_name() == name)?;
    // A page is rendered a few times by a process that then ends: its name may live as
    // long.
    Some(sub.clone().name(&*format!("meshvol-{name}").leak()))
}

fn render(page: Command) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::new();
    clap_mangen::Man::new(page).render(&mut out)?;
    Ok(out)
}

/// Writes `bytes` to stdout; a closed stdout (piped into `head`) ends quietly.
fn emit(bytes: &[u8]) -> ExitCode {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    let _ = stdout.write_all(bytes).and_then(|()| stdout.flush());
    ExitCode::SUCCESS
}
