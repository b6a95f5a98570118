//! `signorini` command line: parse arguments, call the library, map errors
//! to exit codes (0 success, 1 error in the input or the solve, 2 usage).

use clap::{CommandFactory, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};
use signorini::output::describe::counted;
use signorini::output::{ConvergedIncrement, Cut, Iteration, StepObserver, Summary};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

#[derive(Parser)]
#[command(
    name = "signorini",
    // `signorini 0.1.0 (commit 0123456789ab, features: none)`
    version = signorini::output::provenance::VERSION_LINE,
    about = "Nonlinear 3D contact mechanics by finite elements"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case: write a VTU per converged increment, a .pvd series,
    /// summary.json and convergence.svg.
    Run {
        /// The TOML case file, or an Abaqus/CalculiX deck (.inp) run with
        /// its own physics.
        case: PathBuf,
        /// Output folder (default: the case's [output].folder, else
        /// `results` beside the case file).
        #[arg(long)]
        output: Option<PathBuf>,
        /// Worker threads for assembly and factorisation (default: all cores;
        /// at most 4 × the cores, and at most 1024).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
        threads: Option<u32>,
        /// No progress bar and no log lines.
        #[arg(long)]
        quiet: bool,
        /// Resume from the last converged increment of the run whose output
        /// folder DIR is (its NAME.checkpoint), writing on into DIR.
        #[arg(long, value_name = "DIR")]
        restart: Option<PathBuf>,
        /// PETSc options after `--` (e.g. `-- -ksp_type cg -pc_type gamg
        /// -ksp_rtol 1e-10`), read after PETSC_OPTIONS and the case's
        /// [solver.petsc] options (build with `--features petsc`).
        #[arg(last = true, value_name = "PETSC_OPTIONS", allow_hyphen_values = true)]
        petsc: Vec<String>,
    },
    /// Validate the case and its mesh without solving; print what was read.
    Check {
        /// The TOML case file, or an Abaqus/CalculiX deck (.inp).
        case: PathBuf,
    },
    /// Write the case file (TOML) equivalent to an Abaqus/CalculiX deck,
    /// with the deck as its mesh: the same answer as running the deck.
    Convert {
        /// The deck (.inp).
        deck: PathBuf,
        /// The case file to write (default: the deck's name with .toml,
        /// beside it).
        #[arg(long)]
        output: Option<PathBuf>,
        /// Overwrite the case file if it exists.
        #[arg(long)]
        force: bool,
    },
    /// Print the shell completion script (e.g. `signorini completions bash >
    /// ~/.local/share/bash-completion/completions/signorini`).
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
    },
    /// Print the man page in roff (`signorini man > signorini.1`), or a
    /// subcommand's (`signorini man run > signorini-run.1`).
    Man {
        /// A subcommand (run, check, convert, completions).
        subcommand: Option<String>,
    },
}

/// `malloc` with huge pages on large blocks: fewer page faults, the same
/// memory and bits (`signorini::run::huge_pages`).
#[global_allocator]
static ALLOCATOR: signorini::run::huge_pages::HugePageAdvice =
    signorini::run::huge_pages::HugePageAdvice;

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            case,
            output,
            threads,
            quiet,
            restart,
            petsc,
        } => {
            let limit = max_threads();
            if let Some(t) = threads.filter(|&t| t as usize > limit) {
                eprintln!(
                    "error: --threads {t}: at most {limit} (4 × the {} cores available, and at most \
                     {MAX_THREADS}); leave --threads out to use every core",
                    cores()
                );
                return ExitCode::from(2);
            }
            if let Err(message) = petsc_command_line(&petsc) {
                eprintln!("error: {message}");
                return ExitCode::from(2);
            }
            // under mpirun, rank 0 alone shows progress and the result
            let quiet = quiet || signorini::run::launched_rank().is_some_and(|r| r > 0);
            run(case, output, threads, quiet, restart)
        }
        Command::Check { case } => check(case),
        Command::Convert {
            deck,
            output,
            force,
        } => convert(deck, output, force),
        Command::Completions { shell } => return print(&completions(shell)),
        Command::Man { subcommand } => {
            return match man_page(subcommand.as_deref()) {
                Ok(page) => print(&page),
                Err(message) => {
                    eprintln!("error: {message}");
                    ExitCode::from(2)
                }
            };
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // stopped by Ctrl-C or SIGTERM: the shell's code for SIGINT
        Err(e @ signorini::Error::Interrupted { .. }) => {
            eprintln!("stopped: {e}");
            ExitCode::from(130)
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

/// The completion script of `shell` for this command line, generated
/// from its clap definition (every subcommand and flag).
fn completions(shell: clap_complete::Shell) -> Vec<u8> {
    let mut script = Vec::new();
    clap_complete::generate(shell, &mut Cli::command(), "signorini", &mut script);
    script
}

/// The roff man page of the command line, or of one of its subcommands
/// (`signorini-run(1)`, …); an error naming the subcommands for another
/// name.
fn man_page(subcommand: Option<&str>) -> Result<Vec<u8>, String> {
    let cli = Cli::command();
    let command = match subcommand {
        None => cli,
        Some(name) => {
            let names: Vec<&str> = cli.get_subcommands().map(|c| c.get_name()).collect();
            let sub = cli
                .find_subcommand(name)
                .ok_or_else(|| format!("no subcommand '{name}': one of {}", names.join(", ")))?;
            // signorini-run(1), its synopsis `signorini run …`
            sub.clone()
                .display_name(format!("signorini-{name}"))
                .bin_name(format!("signorini {name}"))
        }
    };
    let mut page = Vec::new();
    clap_mangen::Man::new(command)
        // the page's footer: `signorini 0.1.0 (commit …, features: …)`
        .source(format!(
            "signorini {}",
            signorini::output::provenance::VERSION_LINE
        ))
        .render(&mut page)
        .map_err(|e| format!("cannot render the man page: {e}"))?;
    Ok(page)
}

/// Write `bytes` to the standard output: success, or exit code 1 with
/// the reason (a closed pipe, as in `signorini man | head`, is success).
fn print(bytes: &[u8]) -> ExitCode {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: cannot write to the standard output: {e}");
            ExitCode::from(1)
        }
    }
}

/// Hand the PETSc options given after `--` to the PETSc backend; an error
/// without it, or for an argument that is not a PETSc option or its value.
fn petsc_command_line(options: &[String]) -> Result<(), String> {
    if options.is_empty() {
        return Ok(());
    }
    if !options[0].starts_with('-') {
        return Err(format!(
            "'{}' after `--`: PETSc options start with '-' (e.g. `-- -ksp_type cg -pc_type gamg`)",
            options[0]
        ));
    }
    #[cfg(feature = "petsc")]
    {
        signorini::solve::petsc::set_command_line_options(options);
        Ok(())
    }
    #[cfg(not(feature = "petsc"))]
    Err(format!(
        "PETSc options after `--` ({}) need signorini built with PETSc: `cargo build --release \
         --features petsc` (PETSc from `apt-get install petsc-dev`)",
        options.join(" ")
    ))
}

/// The most worker threads `--threads` accepts on any machine: more only
/// adds scheduling overhead (and 100 000 threads load the machine for
/// minutes before anything is solved).
const MAX_THREADS: usize = 1024;

/// The cores available to this process.
fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The largest `--threads` accepted: 4 × the cores, at most [`MAX_THREADS`].
fn max_threads() -> usize {
    (4 * cores()).min(MAX_THREADS)
}

fn run(
    case: PathBuf,
    output: Option<PathBuf>,
    threads: Option<u32>,
    quiet: bool,
    restart: Option<PathBuf>,
) -> signorini::Result<()> {
    // Ctrl-C (SIGINT) and SIGTERM stop the run between two Newton
    // iterations: summary.json says "interrupted", every converged
    // increment stays written
    let cancel = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&cancel);
    // only fails when a handler is already set, which cannot happen here;
    // without one a signal ends the process as before
    let _ = ctrlc::set_handler(move || flag.store(true, Ordering::Relaxed));
    let options = signorini::run::RunOptions {
        output,
        threads: threads.map(|t| t as usize),
        cancel: Some(cancel),
        restart,
    };
    let mut progress = Progress::new(quiet);
    let outcome = signorini::run::run_observed(&case, &options, &mut progress)?;
    progress.bar.finish_and_clear();
    if !quiet {
        let s = &outcome.summary;
        println!(
            "done: {}, {} in {:.2} s; results in {}",
            counted(s.increments.len(), "increment"),
            counted(
                s.increments.iter().map(|i| i.iterations).sum::<usize>(),
                "Newton iteration"
            ),
            s.wall_time,
            outcome.output_dir.display()
        );
    }
    Ok(())
}

/// The terminal's view of a run: a progress bar over pseudo-time and a
/// line per converged (or cut) increment.
struct Progress {
    bar: ProgressBar,
    quiet: bool,
    /// The end time of the last step (the bar's full length).
    end: f64,
    /// Newton iterations of the increment under way.
    iteration: usize,
}

impl Progress {
    fn new(quiet: bool) -> Self {
        let bar = if quiet {
            ProgressBar::hidden()
        } else {
            let bar = ProgressBar::new(1000);
            if let Ok(style) =
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} t = {msg}")
            {
                bar.set_style(style);
            }
            // the clock keeps running while an increment iterates
            bar.enable_steady_tick(std::time::Duration::from_millis(250));
            bar
        };
        Progress {
            bar,
            quiet,
            end: 1.0,
            iteration: 0,
        }
    }

    fn log(&self, line: &str) {
        if self.quiet {
            return;
        }
        if self.bar.is_hidden() {
            eprintln!("{line}");
        } else {
            self.bar.println(line);
        }
    }
}

impl StepObserver for Progress {
    fn on_start(&mut self, _: &Summary) -> signorini::Result<()> {
        Ok(())
    }

    fn on_increment(
        &mut self,
        increment: &ConvergedIncrement,
        _: &Summary,
    ) -> signorini::Result<()> {
        let record = increment.record;
        self.end = increment.problem.steps.last().map_or(1.0, |s| s.end_time);
        self.bar
            .set_position((1000.0 * record.time / self.end) as u64);
        self.bar
            .set_message(format!("{:.4} ({})", record.time, record.step_name));
        let final_residual = record.newton.last().map_or(0.0, |r| r.residual);
        self.log(&format!(
            "step '{}'  t = {:.6}  Δt = {:.3e}  iterations {:2}  residual {:.2e}{}",
            record.step_name,
            record.time,
            record.increment,
            record.iterations,
            final_residual,
            signorini::output::log::lu_fallback_note(increment)
        ));
        Ok(())
    }

    fn on_cut(&mut self, cut: &Cut) {
        self.iteration = 0;
        self.log(&format!(
            "step '{}'  t = {:.6}  Δt = {:.3e}  not converged ({}): cutting the increment",
            cut.step, cut.time, cut.increment, cut.reason
        ));
    }

    fn on_message(&mut self, line: &str) {
        self.log(line);
    }

    fn on_iteration(&mut self, it: &Iteration) {
        self.iteration += 1;
        self.bar.set_message(format!(
            "{:.4} ({}), Newton iteration {}: residual {:.2e}",
            it.time, it.step, self.iteration, it.record.residual
        ));
    }
}

/// `signorini convert`: the deck's case written as TOML beside it (or at
/// `output`), its `[mesh] file` the deck relative to the case file.
fn convert(deck: PathBuf, output: Option<PathBuf>, force: bool) -> signorini::Result<()> {
    let target = output.unwrap_or_else(|| deck.with_extension("toml"));
    if target.exists() && !force {
        return Err(signorini::Error::Case {
            path: target,
            message:
                "exists already: choose another file with --output, or overwrite it with --force"
                    .into(),
        });
    }
    let mesh_file = signorini::case::deck::mesh_path(&deck, &target);
    let translated = signorini::case::deck::translate_file(&deck, &mesh_file)?;
    let mut text = format!(
        "# The case of {} (signorini convert); running it gives the deck's answer.\n",
        deck.display()
    );
    for note in &translated.notes {
        text.push_str(&format!("# note: {note}\n"));
    }
    text.push('\n');
    text.push_str(&signorini::case::deck::to_toml(&translated.spec));
    std::fs::write(&target, &text).map_err(|e| signorini::Error::io("write", &target, e))?;
    for note in &translated.notes {
        println!("note: {note}");
    }
    println!("wrote {}", target.display());
    Ok(())
}

fn check(case: PathBuf) -> signorini::Result<()> {
    let loaded = signorini::case::load(&case)?;
    // as the run will have it (its solution path chosen), with everything
    // the run validates before it solves, so that check refuses what run
    // would (tests/bad_inputs.rs)
    let simulation = signorini::run::Simulation::from_case(&loaded)?;
    let (problem, requests) = (simulation.problem(), simulation.requests());
    let mesh = &problem.model.mesh;
    for note in &loaded.notes {
        println!("note: {note}");
    }
    for warning in loaded.diagnose(problem) {
        println!("warning: {warning}");
    }
    println!("case      {}", case.display());
    println!("nodes     {}", mesh.num_nodes());
    println!("elements  {}", mesh.elements.len());
    println!(
        "dofs      {} ({} prescribed)",
        problem.model.num_dofs(),
        problem.constrained_dofs().iter().filter(|&&c| c).count()
    );
    println!("the model in words:");
    for line in signorini::output::describe::describe_model(problem) {
        println!("  {line}");
    }
    for h in &requests.histories {
        println!(
            "history   {}: {} {}",
            h.name,
            h.label,
            h.location(&mesh.nodes)
        );
    }
    for p in &requests.profiles {
        println!(
            "profile   {}: {} nodes of interface '{}'",
            p.name,
            p.nodes.len(),
            p.interface_name
        );
    }
    println!("ok: the case is valid");
    Ok(())
}
