package mcstat

// #include <mcstat.h>
import "C"

import (
	"fmt"
	"unsafe"
)

// VersionNumber is MAJOR*10000 + MINOR*100 + PATCH of the linked library.
func VersionNumber() uint { return uint(C.mcstat_version_number()) }

// CheckABI compares the size of every struct this package was compiled
// with (mcstat.h at build time) with the linked library's: a mismatch
// means the program runs against a libmcstat of another ABI than its
// header's.  nil when they agree.
func CheckABI() error {
	sizes := []struct {
		name        string
		lib, header uintptr
	}{
		{"mcstat_moments", uintptr(C.mcstat_sizeof_moments()), unsafe.Sizeof(C.struct_mcstat_moments{})},
		{"mcstat_result", uintptr(C.mcstat_sizeof_result()), unsafe.Sizeof(C.struct_mcstat_result{})},
		{"MCSTAT_MOMENTS_BYTES", uintptr(C.mcstat_sizeof_moments_bytes()), C.MCSTAT_MOMENTS_BYTES},
		{"mcstat_stream", uintptr(C.mcstat_sizeof_stream()), unsafe.Sizeof(C.struct_mcstat_stream{})},
		{"mcstat_ks_options", uintptr(C.mcstat_sizeof_ks_options()), unsafe.Sizeof(C.struct_mcstat_ks_options{})},
		{"mcstat_power_options", uintptr(C.mcstat_sizeof_power_options()),
			unsafe.Sizeof(C.struct_mcstat_power_options{})},
		{"mcstat_diag_options", uintptr(C.mcstat_sizeof_diag_options()), unsafe.Sizeof(C.struct_mcstat_diag_options{})},
		{"mcstat_diagnostics", uintptr(C.mcstat_sizeof_diagnostics()), unsafe.Sizeof(C.struct_mcstat_diagnostics{})},
		{"mcstat_gof_options", uintptr(C.mcstat_sizeof_gof_options()), unsafe.Sizeof(C.struct_mcstat_gof_options{})},
		{"mcstat_check_options", uintptr(C.mcstat_sizeof_check_options()),
			unsafe.Sizeof(C.struct_mcstat_check_options{})},
		{"mcstat_check_model", uintptr(C.mcstat_sizeof_check_model()), unsafe.Sizeof(C.struct_mcstat_check_model{})},
		{"mcstat_check_report", uintptr(C.mcstat_sizeof_check_report()),
			unsafe.Sizeof(C.struct_mcstat_check_report{})},
		{"mcstat_seq_options", uintptr(C.mcstat_sizeof_seq_options()), unsafe.Sizeof(C.struct_mcstat_seq_options{})},
		{"mcstat_seq", uintptr(C.mcstat_sizeof_seq()), unsafe.Sizeof(C.struct_mcstat_seq{})},
	}
	for _, s := range sizes {
		if s.lib != s.header {
			return invalid(fmt.Sprintf("%s is %d bytes in the linked libmcstat %s, %d in the header this package "+
				"was built with", s.name, s.lib, Version(), s.header))
		}
	}
	return nil
}

// GSLHandlerOff turns GSL's process-wide error handler off (GSL's default
// aborts the process).  libmcstat never reaches it; this is for programs
// that also call GSL themselves.
func GSLHandlerOff() { C.mcstat_gsl_handler_off() }

// GSLHandlerOffIfDefault turns GSL's handler off only if no handler was
// installed, and reports whether it did.
func GSLHandlerOffIfDefault() bool { return C.mcstat_gsl_handler_off_if_default() != 0 }
