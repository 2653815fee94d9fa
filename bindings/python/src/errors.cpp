// errors.cpp - status codes to the exception classes of mcstat/_errors.py.
//
// Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
#include "common.hpp"

#include <cstring>

namespace mcs {

namespace {
constexpr int N_STATUS = 12; // MCSTAT_OK .. MCSTAT_EHEAVYTAIL
py::handle g_classes[N_STATUS];
py::handle g_base;
} // namespace

void init_errors()
{
    py::module_ errors = py::module_::import("mcstat._errors");
    py::dict by_status = errors.attr("_BY_STATUS");
    g_base = py::object(errors.attr("McstatError")).release();
    for (int s = 0; s < N_STATUS; s++) {
        py::int_ key(s);
        g_classes[s] = by_status.contains(key) ? py::object(by_status[key]).release() : g_base;
    }
}

py::handle error_class(int status)
{
    if (status >= 0 && status < N_STATUS && g_classes[status])
        return g_classes[status];
    return g_base;
}

const char *status_text(int status)
{
    // Python's words where libmcstat's sentence speaks of C (NULL pointers)
    // or of other tests (its too-few sentence lists the K-S and chi-squared
    // rules): the message's detail then says what was wrong, naming the
    // argument.  The other sentences are libmcstat's.
    switch (status) {
    case MCSTAT_EINVAL: return "invalid argument";
    case MCSTAT_ETOOFEW: return "too few observations";
    default: return mcstat_strerror(status);
    }
}

void throw_status(int status, const std::string &detail)
{
    std::string msg = status_text(status);
    if (!detail.empty())
        msg += " (" + detail + ")";
    PyErr_SetString(error_class(status).ptr(), msg.c_str());
    throw py::error_already_set();
}

void throw_refusal(int status, const std::string &fallback)
{
    std::string why = mcstat_last_error();
    if (why.empty())
        throw_status(status, fallback);
    for (const char *prefix : {"options.", "model."})
        if (why.compare(0, std::strlen(prefix), prefix) == 0)
            why.erase(0, std::strlen(prefix));
    PyErr_SetString(error_class(status).ptr(), why.c_str());
    throw py::error_already_set();
}

void throw_invalid(const std::string &message)
{
    // The message names the argument and its domain; the class says the rest.
    PyErr_SetString(error_class(MCSTAT_EINVAL).ptr(), message.c_str());
    throw py::error_already_set();
}

} // namespace mcs
