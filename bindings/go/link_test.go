package mcstat

import (
	"bufio"
	"debug/elf"
	"os"
	"os/exec"
	"path/filepath"
	"strings"
	"testing"
)

// The test binary finds libmcstat through the run path mcstat-rpath.pc
// gives, with no LD_LIBRARY_PATH: the run path names pkg-config's libdir,
// and the library mapped into this process is the one there.
func TestLinkedThroughRunPath(t *testing.T) {
	out, err := exec.Command("pkg-config", "--variable=libdir", "mcstat-rpath").Output()
	if err != nil {
		t.Skipf("pkg-config: %v", err)
	}
	libdir := realDir(t, strings.TrimSpace(string(out)))
	exe, err := os.Executable()
	if err != nil {
		t.Fatal(err)
	}
	f, err := elf.Open(exe)
	if err != nil {
		t.Fatal(err)
	}
	defer f.Close()
	var paths []string
	for _, tag := range []elf.DynTag{elf.DT_RUNPATH, elf.DT_RPATH} {
		v, _ := f.DynString(tag)
		for _, s := range v {
			paths = append(paths, strings.Split(s, ":")...)
		}
	}
	found := false
	for _, p := range paths {
		if p != "" && realDir(t, p) == libdir {
			found = true
		}
	}
	if !found {
		t.Errorf("the test binary's run path %q does not name %s", paths, libdir)
	}
	if os.Getenv("LD_LIBRARY_PATH") != "" {
		return // the loader may have taken the library from there
	}
	maps, err := os.Open("/proc/self/maps")
	if err != nil {
		t.Skip(err)
	}
	defer maps.Close()
	sc := bufio.NewScanner(maps)
	for sc.Scan() {
		fields := strings.Fields(sc.Text())
		if p := fields[len(fields)-1]; strings.Contains(filepath.Base(p), "libmcstat.so") {
			if got := realDir(t, filepath.Dir(p)); got != libdir {
				t.Errorf("libmcstat loaded from %s, pkg-config's libdir is %s", got, libdir)
			}
			return
		}
	}
	t.Error("libmcstat.so is not mapped into the process")
}

func realDir(t *testing.T, p string) string {
	r, err := filepath.EvalSymlinks(p)
	if err != nil {
		return filepath.Clean(p)
	}
	return r
}
