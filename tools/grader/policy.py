"""What a compiled lab file may contain, define and call (the Grading page, "What student code may
use"): the allowed sections, C functions and standard-library names, the refused families with the
reason each is refused, and the instructions that enter the kernel.
"""

import re

# Sections a compiled lab file may contain. Anything else (.preinit_array, prioritised
# .init_array.NNNNN, .ctors, .init, linker directives) could run code before the harness or change
# the link, and is refused.
ALLOWED_SECTIONS = re.compile(
    r"^(|\.text(\..*)?|\.data(\..*)?|\.bss(\..*)?|\.rodata(\..*)?|\.tdata(\..*)?|\.tbss(\..*)?|"
    r"\.init_array|\.fini_array|\.eh_frame|\.gcc_except_table(\..*)?|\.group|\.note\.GNU-stack|"
    r"\.note\.gnu\.property|\.comment|\.rela?\..*|\.symtab|\.strtab|\.shstrtab|\.debug_.*)$")

# What a lab file may reference beyond the framework's API and its own code (the Grading page,
# "What student code may use"): the C++ standard library's containers, strings, string streams,
# the standard streams, exceptions and allocation; libm; and the C functions below. Nothing that
# reaches files, processes, signals, memory maps, dynamic loading, threads, the environment or the
# kernel directly: a test process then cannot end itself with a status of its choosing, write to a
# descriptor it was not given, or read what it may not.
ALLOWED_C = frozenset("""
    malloc calloc realloc free aligned_alloc posix_memalign memalign
    memcpy memmove memset memcmp memchr strlen strnlen strcmp strncmp strchr strrchr strstr
    strcpy strncpy strcat strncat strtod strtof strtold strtol strtoll strtoul strtoull
    atof atoi atol atoll sscanf __isoc99_sscanf __isoc23_sscanf __isoc99_vsscanf __isoc23_vsscanf
    __isoc23_strtol __isoc23_strtoll __isoc23_strtoul __isoc23_strtoull
    snprintf sprintf vsnprintf vsprintf printf vprintf puts putchar fprintf vfprintf fputs fputc
    fwrite fflush stdout stderr __printf_chk __vprintf_chk __fprintf_chk __vfprintf_chk
    __snprintf_chk __sprintf_chk __vsnprintf_chk __vsprintf_chk __memcpy_chk __memmove_chk
    __memset_chk __strcpy_chk __strncpy_chk __strcat_chk __strncat_chk
    abort __assert_fail __stack_chk_fail qsort bsearch abs labs llabs div ldiv rand srand
    clock time clock_gettime gettimeofday __errno_location
    __ctype_b_loc __ctype_tolower_loc __ctype_toupper_loc tolower toupper isalpha isdigit isspace
    __gxx_personality_v0 _Unwind_Resume __dso_handle __libc_single_threaded __tls_get_addr
    _GLOBAL_OFFSET_TABLE_ __cxa_atexit __cxa_finalize __cxa_thread_atexit_impl __dynamic_cast
""".split())
# Demangled names of the C++ runtime a lab file may reference (the standard library as its
# headers instantiate it), less the parts that reach the system (FORBIDDEN_STD).
ALLOWED_STD = re.compile(r"^(?:(?:typeinfo|typeinfo name|vtable|VTT|construction vtable) for )?"
                         r"(?:std::|__gnu_cxx::|__cxxabiv1::|operator new|operator delete|__cxa_)")
# An instantiation of a standard-library template (a weak copy the headers make, never a C function).
STD_INSTANCE = re.compile(r"^(?:std::|__gnu_cxx::)[^(]*<")
# The framework's and the labs' own names (their vtables and type information included).
PHYSLAB_NAME = re.compile(r"^(?:(?:typeinfo|typeinfo name|vtable|VTT|construction vtable) for )?physlab::")
FORBIDDEN_STD = re.compile(
    r"^(?:(?:typeinfo|typeinfo name|vtable|VTT|construction vtable) for )?"
    r"(?:std::(?:__cxx11::)?(?:basic_filebuf|basic_ifstream|basic_ofstream|basic_fstream|"
    r"__basic_file|filesystem|experimental::filesystem|thread|this_thread|jthread|"
    r"condition_variable|mutex|recursive_mutex|timed_mutex|shared_mutex|__future_base|"
    r"__atomic_futex|__once_|call_once|set_terminate|set_unexpected|set_new_handler|"
    r"quick_exit|_Exit|exit|at_quick_exit|atexit|system)|"
    r"__gnu_cxx::stdio_(?:sync_)?filebuf)")
# Why a refused symbol is refused, by family (the first match names it).
FORBIDDEN_WHY = [
    (re.compile(r"exit|^_Exit"), "it ends the process; throw an exception instead"),
    (re.compile(r"^dl|_dl_|dl_iterate_phdr|_r_debug|_DYNAMIC|link_map"),
     "it loads code or walks the loaded objects"),
    (re.compile(r"fork|exec|spawn|system|popen|wait|kill|clone|daemon|setsid|setpgid|"
                r"setuid|setgid|ptrace|prctl|setrlimit|prlimit"),
     "it reaches other processes or the process itself"),
    (re.compile(r"signal|sigaction|sigprocmask|raise|alarm|setitimer|sigsuspend|pause|longjmp|setjmp"),
     "it handles signals or jumps out of the harness"),
    (re.compile(r"mmap|munmap|mprotect|mremap|madvise|brk|sbrk|shm|memfd|process_vm"),
     "it maps or protects memory"),
    (re.compile(r"syscall"), "it is a raw system call"),
    (re.compile(r"thread|mutex|cond|once|futex|sem_"),
     "it starts or synchronises threads; lab code is single-threaded"),
    (re.compile(r"env|environ|getpid|getuid|uname|hostname|socket|connect|bind|listen|accept|send|recv"),
     "it reaches the environment or the network"),
    (re.compile(r"open|creat|close|read|write|seek|stat|unlink|remove|rename|mkdir|rmdir|chdir|"
                r"link|chmod|chown|dup|pipe|fcntl|ioctl|sendfile|splice|truncate|sync|getdents|"
                r"filebuf|fstream|__basic_file|filesystem|FILE|tmp|opendir|readdir|fopen|fdopen|"
                r"freopen|fscanf|fgets|fread|getline|getchar|scanf"),
     "it reaches files; lab code reads and writes none"),
]
# Instructions that enter the kernel: no lab file needs one, and only inline assembly writes one.
KERNEL_ENTRY_RE = re.compile(r"^\s*[0-9a-f]+:\s+(syscall|sysenter|int\s+\$0x[0-9a-f]+|int1|vmcall)\b",
                             re.MULTILINE)
ASM_KEYWORD_RE = re.compile(r"\b(asm|__asm|__asm__)\b")


def why_refused(name: str) -> str:
    if PHYSLAB_NAME.match(name):
        return "it is framework code that writes files or runs programs (plots, demo output), which no lab file needs"
    for pattern, why in FORBIDDEN_WHY:
        if pattern.search(name):
            return why
    return "it is not among the functions a lab file may use (see the Grading page)"
